// uniform_strategy.h — the `uniform` emission strategy (DESIGN.md §3.1, the paper's "no
// optimisation"): every path starts on the disk orthogonal to its direction that covers the
// scene's bounding sphere; the sun or a sky cell is chosen in proportion to its flux through it.
// Tables: source_table.h; device half: kernels/lib/emit_uniform.h.
#pragma once

#include <memory>

#include "emission/strategy.h"

namespace fen {

std::unique_ptr<EmissionStrategy> makeUniformStrategy(const EmissionInputs& in);

}  // namespace fen
