// sensor_smoothing.h — a sensor grid's cells smoothed by local linear regression (DESIGN.md §8),
// `--sensor-smoothing R`: each cell's value is replaced by the value at its centre of the plane
// a + b u + c v fitted, by least squares with tricube weights (1 - (d/R)^3)^3, to the cells of the
// same sensor and plane whose centres lie within R of it. A linear operator on the cells, applied
// to every batch alike, so each smoothed cell keeps a standard error from its batches' spread.
// What it trades: noise for a bias of about R^2/10 times the field's curvature -- none where the
// illuminance varies linearly, and, unlike a larger cell, no leak across a wall: only cells of the
// grid take part, and only those the cell sees (the segment between their centres meets no
// triangle of the scene: one grid may span two rooms, a wall between them). No first-order bias
// at the grid's edges either: the fit is linear, not a mean, and narrows across an edge. Off
// by default: a cell's own value is unbiased. Where fewer than three cells span a plane around a
// cell, the fit falls back to the weighted mean of what there is.
#pragma once

#include <cstdint>
#include <vector>

#include "sensor/sensor_set.h"

namespace fen {

class SensorSmoother {
public:
    // `scene`: the geometry that separates cells (null: none does).
    SensorSmoother(const SensorSet& set, double radius_m, const Scene* scene);
    double radius() const { return radius_; }
    // The smoothed cells: out[c] = sum over its neighbours n of weight(c, n) in[n].
    std::vector<double> apply(const std::vector<double>& in) const;
    // The mean number of cells a cell's fit uses.
    double meanNeighbours() const;

private:
    double radius_;
    std::vector<std::uint32_t> first_;  // cell c's weights are [first_[c], first_[c + 1])
    std::vector<std::uint32_t> cell_;
    std::vector<double> weight_;
};

}  // namespace fen
