// portal_strategy.h — the `portal` emission strategy (DESIGN.md §3.2, the paper's method 1):
// every path starts through a user-marked portal, by eqs. (1)-(2) (tables: portal_emission.h;
// device half: kernels/lib/emit_portal.h), with the overlap of portals along a line corrected by
// rejection or by weighting.
#pragma once

#include <memory>

#include "emission/strategy.h"

namespace fen {

std::unique_ptr<EmissionStrategy> makePortalStrategy(const EmissionSettings& settings,
                                                     const EmissionInputs& in);

}  // namespace fen
