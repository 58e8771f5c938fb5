// device_sensors.cpp — sensor tables and accumulators on the device (device_sensors.h).
#include "sensor/device_sensors.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "util/error.h"
#include "util/fixed_point.h"
#include "util/float4.h"

namespace fen {

SensorTables makeSensorTables(const SensorSet& set, float fixedScale)
{
    SensorTables t;
    t.info.cells = static_cast<std::uint32_t>(set.cells.size());
    t.info.fixed_scale = fixedScale;
    t.cells.resize(set.cells.size());
    // Cells by plane: normal and offset to 1e-4.
    using Key = std::tuple<long long, long long, long long, long long>;
    std::map<Key, std::vector<std::uint32_t>> byPlane;
    for (std::uint32_t i = 0; i < set.cells.size(); ++i) {
        const SensorCell& c = set.cells[i];
        const double d = glm::dot(c.normal, c.position);
        byPlane[{std::llround(c.normal.x * 1e4), std::llround(c.normal.y * 1e4), std::llround(c.normal.z * 1e4),
                 std::llround(d * 1e4)}]
            .push_back(i);
    }
    for (const auto& [key, members] : byPlane) {
        const SensorCell& first = set.cells[members.front()];
        const glm::dvec3 n = first.normal;
        glm::dvec3 u, v;
        sensorPlaneAxes(n, &u, &v);
        const double d = glm::dot(n, first.position);
        // The cells' squares in plane coordinates about a point of the plane.
        const glm::dvec3 p0 = n * d;
        double ulo = INFINITY, vlo = INFINITY, uhi = -INFINITY, vhi = -INFINITY, side = 0.0;
        for (std::uint32_t i : members) {
            const SensorCell& c = set.cells[i];
            const double h = 0.5 * c.side_m;
            const double cu = glm::dot(c.position - p0, u), cv = glm::dot(c.position - p0, v);
            ulo = std::min(ulo, cu - h);
            uhi = std::max(uhi, cu + h);
            vlo = std::min(vlo, cv - h);
            vhi = std::max(vhi, cv + h);
            side = std::max(side, c.side_m);
        }
        double bucket = side;
        const auto count = [&](double b, double ext) { return std::max(1.0, std::ceil(ext / b)); };
        while (count(bucket, uhi - ulo) * count(bucket, vhi - vlo) > 4.0 * static_cast<double>(members.size()) + 16.0)
            bucket *= 2.0;
        const std::uint32_t cols = static_cast<std::uint32_t>(count(bucket, uhi - ulo));
        const std::uint32_t rows = static_cast<std::uint32_t>(count(bucket, vhi - vlo));
        const glm::dvec3 corner = p0 + ulo * u + vlo * v;
        dev::DevSensorPlane pl{};
        pl.origin = toFloat4(corner, d);
        pl.normal = toFloat4(n, 1.0 / bucket);
        pl.u_axis = toFloat4(u, 0.0);
        pl.v_axis = toFloat4(v, 0.0);
        pl.bucket_first = static_cast<std::uint32_t>(t.bucketStart.size());
        pl.cols = cols;
        pl.rows = rows;
        // Counting sort of (bucket, cell) pairs: every bucket a cell's square overlaps.
        std::vector<std::vector<std::uint32_t>> lists(static_cast<std::size_t>(cols) * rows);
        for (std::uint32_t i : members) {
            const SensorCell& c = set.cells[i];
            const double h = 0.5 * c.side_m;
            const double cu = glm::dot(c.position - corner, u), cv = glm::dot(c.position - corner, v);
            t.cells[i] = {static_cast<float>(cu), static_cast<float>(cv), static_cast<float>(h),
                          static_cast<float>(1.0 / (c.side_m * c.side_m))};
            const auto clampIndex = [](double x, std::uint32_t n) {
                return static_cast<std::uint32_t>(std::clamp(std::floor(x), 0.0, static_cast<double>(n - 1)));
            };
            const std::uint32_t i0 = clampIndex((cu - h) / bucket, cols), i1 = clampIndex((cu + h) / bucket, cols);
            const std::uint32_t j0 = clampIndex((cv - h) / bucket, rows), j1 = clampIndex((cv + h) / bucket, rows);
            for (std::uint32_t j = j0; j <= j1; ++j)
                for (std::uint32_t k = i0; k <= i1; ++k)
                    lists[static_cast<std::size_t>(j) * cols + k].push_back(i);
        }
        for (const auto& l : lists) {
            t.bucketStart.push_back(static_cast<std::uint32_t>(t.bucketCells.size()));
            t.bucketCells.insert(t.bucketCells.end(), l.begin(), l.end());
        }
        t.bucketStart.push_back(static_cast<std::uint32_t>(t.bucketCells.size()));
        t.planes.push_back(pl);
    }
    t.info.planes = static_cast<std::uint32_t>(t.planes.size());
    return t;
}

DeviceSensors::DeviceSensors(ocl::Context& ctx) : ctx_(ctx)
{
    upload(ctx, SensorTables{});
}

DeviceSensors::DeviceSensors(ocl::Context& ctx, const SensorSet& set, float fixedScale, int patchMF)
    : ctx_(ctx), cells_(set.cells.size()), patches_(patchMF > 0 ? skyPatchCount(patchMF) : 0), patchMF_(patchMF),
      fixedScale_(fixedScale)
{
    SensorTables t = makeSensorTables(set, fixedScale);
    t.info.patches = static_cast<std::uint32_t>(patches_);
    upload(ctx, t);
}

void DeviceSensors::upload(ocl::Context& ctx, const SensorTables& t)
{
    // OpenCL buffers may not be empty: an empty table gets one unused element.
    const auto make = [&](const auto& v, const char* what) {
        using T = typename std::decay_t<decltype(v)>::value_type;
        std::vector<T> data = v;
        if (data.empty())
            data.resize(1);
        return ctx.buffer(CL_MEM_READ_ONLY, data.size() * sizeof(T), what, data.data());
    };
    info_ = ctx.buffer(CL_MEM_READ_ONLY, sizeof t.info, "sensor info", &t.info);
    planes_ = make(t.planes, "sensor planes");
    cellTable_ = make(t.cells, "sensor cells");
    bucketStart_ = make(t.bucketStart, "sensor buckets");
    bucketCells_ = make(t.bucketCells, "sensor bucket cells");
    accum_ = ctx.buffer(CL_MEM_READ_WRITE, accumWords() * 8,
                        patches_ ? "sensor accumulators and daylight coefficients" : "sensor accumulators");
    // per cell, then (with daylight coefficients) per sky patch: 1 until set
    const std::vector<float> ones(std::max<std::size_t>(cells_ + patches_, 1), 1.0f);
    steer_ = ctx.buffer(CL_MEM_READ_ONLY, ones.size() * 4, "sensor steering", ones.data());
    clear();
}

void DeviceSensors::setSteer(const std::vector<float>& perCell)
{
    if (perCell.size() == cells_ && cells_ > 0)
        ctx_.queue().enqueueWriteBuffer(steer_, CL_TRUE, 0, cells_ * 4, perCell.data());
}

void DeviceSensors::setPatchWeights(const std::vector<float>& perPatch)
{
    if (perPatch.size() == patches_ && patches_ > 0)
        ctx_.queue().enqueueWriteBuffer(steer_, CL_TRUE, cells_ * 4, patches_ * 4, perPatch.data());
}

void DeviceSensors::clear()
{
    ctx_.queue().enqueueFillBuffer(accum_, cl_ulong(0), 0, accumWords() * 8);
}

std::vector<double> DeviceSensors::read(std::uint64_t paths)
{
    std::vector<double> lux(cells_, 0.0);
    if (cells_ == 0)
        return lux;
    std::vector<std::uint64_t> acc(cells_ * 2);
    ctx_.queue().enqueueReadBuffer(accum_, CL_TRUE, 0, acc.size() * 8, acc.data());
    const double toLux = 1.0 / (static_cast<double>(fixedScale_) * static_cast<double>(std::max<std::uint64_t>(paths, 1)));
    for (std::size_t c = 0; c < cells_; ++c)
        lux[c] = fixed128(acc.data() + 2 * c) * toLux;
    return lux;
}

std::vector<double> DeviceSensors::readMatrices(std::uint64_t paths)
{
    const std::size_t block = cells_ * patches_;
    std::vector<double> m(3 * block, 0.0);
    if (block == 0)
        return m;
    std::vector<std::uint64_t> acc(4 * block);
    ctx_.queue().enqueueReadBuffer(accum_, CL_TRUE, cells_ * 16, acc.size() * 8, acc.data());
    const double toLux = 1.0 / (static_cast<double>(fixedScale_) * static_cast<double>(std::max<std::uint64_t>(paths, 1)));
    for (std::size_t k = 0; k < 2 * block; ++k)
        m[k] = fixed128(acc.data() + 2 * k) * toLux;
    // the indirect light: all light less the direct, in the integers (every direct crossing was
    // also added to all light, so the difference is exact and never negative)
    for (std::size_t k = 0; k < block; ++k) {
        const std::uint64_t* all = acc.data() + 2 * k;
        const std::uint64_t* direct = acc.data() + 2 * (block + k);
        m[2 * block + k] = fixed128(sub128({all[0], all[1]}, {direct[0], direct[1]})) * toLux;
    }
    return m;
}

}  // namespace fen
