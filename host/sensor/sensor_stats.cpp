// sensor_stats.cpp — batch statistics of the sensor cells (sensor_stats.h).
#include "sensor/sensor_stats.h"

#include <algorithm>
#include <cmath>

#include "io/state_io.h"

namespace fen {

void SensorStatistics::add(const std::vector<double>& lux, double w)
{
    for (std::size_t c = 0; c < cells_; ++c) {
        sum_[c] += w * lux[c];
        sumSq_[c] += w * lux[c] * lux[c];
    }
    if (keepBatches_)
        batches_.emplace_back(lux.begin(), lux.end());
    weights_.push_back(w);
    weight_ += w;
}

std::vector<double> SensorStatistics::mean() const
{
    std::vector<double> m(cells_, 0.0);
    if (weight_ > 0.0)
        for (std::size_t c = 0; c < cells_; ++c)
            m[c] = sum_[c] / weight_;
    return m;
}

std::vector<double> SensorStatistics::stdErr() const
{
    std::vector<double> se(cells_, 0.0);
    const double B = static_cast<double>(weights_.size()), W = weight_;
    if (B < 2.0)
        return se;
    for (std::size_t c = 0; c < cells_; ++c) {
        const double m = sum_[c] / W;
        const double var = std::max(0.0, (sumSq_[c] - W * m * m) / (B - 1.0));
        se[c] = std::sqrt(var / W);
    }
    return se;
}

SensorStatistics::Estimate SensorStatistics::jackknife(const std::function<double(const std::vector<double>&)>& f) const
{
    Estimate e;
    e.value = f(mean());
    const std::size_t B = weights_.size();
    if (B < 2 || !keepBatches_)
        return e;
    std::vector<double> loo(B), m(cells_);
    double avg = 0.0;
    for (std::size_t b = 0; b < B; ++b) {
        const double W = weight_ - weights_[b];
        for (std::size_t c = 0; c < cells_; ++c)
            m[c] = W > 0.0 ? (sum_[c] - weights_[b] * batches_[b][c]) / W : 0.0;
        loo[b] = f(m);
        avg += loo[b];
    }
    avg /= static_cast<double>(B);
    double ss = 0.0;
    for (double x : loo)
        ss += (x - avg) * (x - avg);
    e.stdErr = std::sqrt(static_cast<double>(B - 1) / static_cast<double>(B) * ss);
    return e;
}

SensorStatistics SensorStatistics::mapped(const std::function<std::vector<double>(const std::vector<double>&)>& f) const
{
    SensorStatistics out(cells_);
    for (std::size_t b = 0; b < batches_.size(); ++b)
        out.add(f(std::vector<double>(batches_[b].begin(), batches_[b].end())), weights_[b]);
    return out;
}

void SensorStatistics::save(StateWriter& w) const
{
    w.u64("sensors.cells", cells_);
    w.u64("sensors.batches", weights_.size());
    w.f64("sensors.weight", weight_);
    w.f64s("sensors.weights", weights_);
    w.f64s("sensors.sum", sum_);
    w.f64s("sensors.sum_sq", sumSq_);
    for (const auto& b : batches_)
        w.f64s("sensors.batch", std::vector<double>(b.begin(), b.end()));
}

void SensorStatistics::load(StateReader& r)
{
    if (r.u64("sensors.cells") != cells_)
        r.fail("sensors.cells", "made with other sensors");
    const std::size_t batches = r.u64("sensors.batches", 1u << 20);
    weight_ = r.f64("sensors.weight");
    weights_ = r.f64s("sensors.weights", batches, true);
    sum_ = r.f64s("sensors.sum", cells_, true);
    sumSq_ = r.f64s("sensors.sum_sq", cells_, true);
    batches_.clear();
    for (std::size_t b = 0; keepBatches_ && b < batches; ++b) {
        const std::vector<double> v = r.f64s("sensors.batch", cells_, true);
        batches_.emplace_back(v.begin(), v.end());
    }
    for (const auto* v : {&sum_, &sumSq_})
        for (double x : *v)
            if (x < 0.0)
                r.fail("sensors.sum", "a negative value: light is never negative");
    for (const auto& b : batches_)
        for (float x : b)
            if (x < 0.0f)
                r.fail("sensors.batch", "a negative value: light is never negative");
    for (double w : weights_)
        if (!(w > 0.0))
            r.fail("sensors.weights", "a batch of no weight");
}

}  // namespace fen
