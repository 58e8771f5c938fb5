// uniform_strategy.h — the `uniform` emission strategy (DESIGN.md §3.1, the paper's "no
// optimisation"): every path enters the box that bounds the scene at a point uniform over the
// box's silhouette seen along its direction; the sun or a sky cell is chosen in proportion to its
// flux into the box. It has no options.
// Tables: uniform_emission.h; device half: kernels/lib/emit_uniform.h.
#pragma once

#include <memory>

#include "emission/strategy.h"
#include "emission/strategy_registry.h"

namespace fen {

// Its descriptor (strategy_registry.h).
extern const StrategyDescriptor kUniformStrategy;

std::unique_ptr<EmissionStrategy> makeUniformStrategy(const EmissionInputs& in);

}  // namespace fen
