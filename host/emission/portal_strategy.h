// portal_strategy.h — the `portal` emission strategy (DESIGN.md §3.2, the paper's method 1):
// every path starts through a user-marked portal, by eqs. (1)-(2) (tables: portal_emission.h;
// device half: kernels/lib/emit_portal.h), with the overlap of portals along a line corrected by
// rejection or by weighting. Options: portal_options.h.
// Its blind spot, measured (DESIGN.md §3.4): a share `complement` of the paths are `uniform`
// paths whose lines cross no portal -- light from outside reflections and unmarked openings. They
// are not added to the image (which stays the paper's estimate) but to the strategy's statistics:
// per batch, the share of the light reaching the camera that they carry. The report gives its
// mean and standard error over the batches as `unreached`; the strategy warns when it is
// significant.
#pragma once

#include <memory>

#include "emission/strategy.h"
#include "emission/strategy_registry.h"

namespace fen {

// Its descriptor (strategy_registry.h).
extern const StrategyDescriptor kPortalStrategy;

std::unique_ptr<EmissionStrategy> makePortalStrategy(const EmissionSettings& settings,
                                                     const EmissionInputs& in);

}  // namespace fen
