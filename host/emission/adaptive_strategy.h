// adaptive_strategy.h — the `adaptive` emission strategy (DESIGN.md §3.3, the paper's method 2):
// emitted rays are drawn from a grid of cells whose probabilities are learned while rendering
// (adaptive_grid.h), over a base strategy that needs no marking (`uniform`) or over the marked
// portals (`portal`) with a share of the disk that keeps it unbiased when the marking is wrong.
//
// The cells (adaptive_grid.h; device half: kernels/lib/emit_adaptive.h): a box of directions -- the
// sun's cone, or a box of (s, t) = (1 - cos(theta), phi / 2 pi) over the sky (s in [1, 2): the
// ground's glow below the horizon, when the sky has one), where equal areas
// are equal solid angles and a direction is drawn uniformly, its radiance g(v) evaluated -- times
// a box of the origin's 2D parametrisation: its own emission disk (radius R, orthogonal to v,
// covering the bounding sphere) through the concentric map, and with a portal base the frame of
// every plane of portal triangles (portal_planes.h). The grid starts with 4^initialSkyDepth sky
// boxes and the sun, each with 4^initialDepth origin boxes per region, and refines where the
// light is.
// The base density P_base(cell): over `uniform`, the direction box's flux (the sky's integral over
// it, the sun's illuminance) times the origin box's area -- `uniform`'s density at the resolution of
// the boxes; over `portal`, (1 - diskShare) times the flux through each plane's triangles (|v.n|,
// plus 5 % so that no plane is written off before anything is measured) plus diskShare times the
// `uniform` density. The fluxes come from a midpoint rule: they shape the base and the priors only;
// paths' weights use the exact density.
// Passes: the first has firstPass paths, each next one twice as many, and every batch ends one;
// after each, the statistics come back and the grid learns; each batch weighs in the image by its
// precision as predicted before it ran (render/film.h).
// Options: adaptive_options.h.
#pragma once

#include <memory>

#include "emission/strategy.h"
#include "emission/strategy_registry.h"

namespace fen {

class AdaptiveStrategy : public EmissionStrategy {
public:
    // The grid the device draws from, with the probabilities it realises (integer alias table).
    virtual const AdaptiveGrid& grid() const = 0;
    virtual const std::vector<double>& realisedProbabilities() const = 0;
    // Replaces the cells' probabilities (normalised; > 0 wherever the base is) and uploads them:
    // a known grid for the tests, a saved one for a resumed render.
    virtual void setProbabilities(const std::vector<double>& p) = 0;
};

std::unique_ptr<AdaptiveStrategy> makeAdaptiveStrategy(const EmissionSettings& settings,
                                                       const EmissionInputs& in);

// Its descriptor (strategy_registry.h).
extern const StrategyDescriptor kAdaptiveStrategy;

}  // namespace fen
