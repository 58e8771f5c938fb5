// sensor_stats.h — the sensors' batch statistics (DESIGN.md §8): each cell's illuminance over the
// batches (their weighted mean, as the film's pixels: render/film.h) with its standard error from
// the batches' spread, and the grid statistics a daylighting study reports -- mean, minimum,
// maximum, uniformity (min / mean), a daylight factor's share above a threshold -- each with a
// jackknife standard error over the batches: the statistic recomputed with each batch left out,
// var = (B - 1) / B sum (s_(b) - s_(.))^2. The jackknife holds for any smooth function of the
// cells' means; for the minimum and maximum it measures the spread, while noise also biases them
// (the minimum of noisy cells is low, the maximum high) by about a cell's standard error.
// Kept per batch as float (for the jackknife; the sums are in double): cells x batches floats.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

namespace fen {

class StateReader;
class StateWriter;

class SensorStatistics {
public:
    // keepBatches false: only the weighted sums are kept (mean, stdErr), not each batch (no
    // jackknife, no mapped(); save() and load() keep the sums alone): for the daylight-coefficient
    // matrices, whose copies per batch would take 16 x cells x patches floats.
    explicit SensorStatistics(std::size_t cells, bool keepBatches = true)
        : cells_(cells), keepBatches_(keepBatches), sum_(cells, 0.0), sumSq_(cells, 0.0) {}
    void add(const std::vector<double>& lux, double weight = 1.0);
    std::size_t cells() const { return cells_; }
    int batches() const { return static_cast<int>(weights_.size()); }
    std::vector<double> mean() const;
    std::vector<double> stdErr() const;  // zero with fewer than two batches

    struct Estimate {
        double value = 0.0, stdErr = 0.0;
    };
    // f of the cells' means, and its jackknife standard error (0 with fewer than two batches).
    Estimate jackknife(const std::function<double(const std::vector<double>&)>& f) const;

    // The statistics of f(batch) for every batch, same weights: a linear f (a smoothing) keeps
    // each output's standard error from the batches' spread.
    SensorStatistics mapped(const std::function<std::vector<double>(const std::vector<double>&)>& f) const;

    void save(StateWriter& w) const;
    void load(StateReader& r);

private:
    std::size_t cells_;
    bool keepBatches_ = true;
    std::vector<double> sum_, sumSq_;  // weighted
    std::vector<std::vector<float>> batches_;
    std::vector<double> weights_;
    double weight_ = 0.0;
};

}  // namespace fen
