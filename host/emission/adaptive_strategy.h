// adaptive_strategy.h — the `adaptive` emission strategy (DESIGN.md §3.3, the paper's method 2):
// emitted rays are drawn from a grid of cells whose probabilities are learned while rendering
// (adaptive_grid.h), over a base strategy that needs no marking (`uniform`) or over the marked
// portals (`portal`) with a share of the disk that keeps it unbiased when the marking is wrong.
//
// The cells (device half: kernels/lib/emit_adaptive.h):
//   - directions: a bin is the sun, or a rectangle of sky -- thetaBins bands of equal solid angle
//     times phiBins azimuth steps. The sky table is refined so that every bin edge is a node (the
//     same bilinear function: a bilinear patch restricted to a sub-rectangle is bilinear), and a
//     path picks one of its bin's sky cells in proportion to the cell's flux (q(k | bin), exact
//     integers), then a direction in the cell as `uniform` does;
//   - origins: the emission disk of `uniform` through the concentric map, and with a portal base
//     the frame (bounding rectangle in its plane) of every plane of portal triangles.
// The base density P_base(cell): over `uniform`, the bin's flux through the disk times the box's
// area; over `portal`, (1 - diskShare) times the flux through each plane's triangles (per bin, its
// flux vector F_b . n, plus 5 % of the bin's flux so that no plane is written off before it is
// measured) times the box, plus diskShare times the `uniform` density.
// Passes: the first has firstPass paths, each next one twice as many, and every batch ends one;
// after each, the statistics come back and the grid learns (adaptive_grid.h).
#pragma once

#include <memory>

#include "emission/strategy.h"

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

// The option ranges, checked before anything is built (fen::Error naming the option).
void validateAdaptiveOptions(const AdaptiveOptions& o);

}  // namespace fen
