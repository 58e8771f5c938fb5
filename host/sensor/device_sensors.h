// device_sensors.h — the sensors on the device (DESIGN.md §8): the plane and bucket tables that
// lib/sensor.h searches, built from a SensorSet, and the cells' 128-bit fixed-point accumulators.
//
// Cells are grouped by plane (normal and offset equal to 1e-4); each plane's bucket grid has
// buckets of the largest cell side there (doubled while the buckets outnumber four per cell, for
// scattered points), and every cell is listed in each bucket its square overlaps. A render without
// sensors binds an empty set (info.planes = 0), and its kernels are built without them.
#pragma once

#include <cstdint>
#include <vector>

#include "cl/context.h"
#include "annual/sky_patches.h"
#include "sensor/sensor_set.h"
#include "shared/fen_sensor.h"
#include "team/summed_buffer.h"

namespace fen {

// The host-side tables, before upload (tested directly: tests/host/sensor_test.cpp).
struct SensorTables {
    dev::DevSensorInfo info{};
    std::vector<dev::DevSensorPlane> planes;
    std::vector<dev::DevSensorCell> cells;
    std::vector<std::uint32_t> bucketStart, bucketCells;
};
SensorTables makeSensorTables(const SensorSet& set, float fixedScale);

class DeviceSensors {
public:
    // No sensors.
    explicit DeviceSensors(ocl::Context& ctx);
    // `fixedScale`: accumulators hold round(lux x paths x fixedScale). `patches` > 0: the
    // daylight-coefficient matrices too (shared/fen_sensor.h), cells x patches each, for paths
    // tagged by Reinhart's subdivision MF = `patchMF` (lib/sky_patch.h; kernels built with it).
    DeviceSensors(ocl::Context& ctx, const SensorSet& set, float fixedScale, int patchMF = 0);

    bool any() const { return cells_ > 0; }
    std::size_t cells() const { return cells_; }
    float fixedScale() const { return fixedScale_; }
    int patchMF() const { return patchMF_; }          // 0: no daylight coefficients
    std::size_t patches() const { return patches_; }  // columns of each matrix
    // Kernel arguments, in this order (kernels/shade.cl, lib/fused_kernel.h).
    const cl::Buffer& info() const { return info_; }
    const cl::Buffer& planes() const { return planes_; }
    const cl::Buffer& cellTable() const { return cellTable_; }
    const cl::Buffer& bucketStart() const { return bucketStart_; }
    const cl::Buffer& bucketCells() const { return bucketCells_; }
    const cl::Buffer& accumulators() const { return accum_; }
    // The accumulators (cells, then the coefficient matrices) as a team sums them: 128-bit each.
    SummedBuffer summed() const { return {&accum_, cells_ ? accumWords() / 2 : 0, {2}}; }
    // Each cell's factor on what it adds to a learning strategy's statistics (lib/sensor.h): 1
    // (the absolute target) until setSteer() says otherwise.
    const cl::Buffer& steer() const { return steer_; }
    void setSteer(const std::vector<float>& perCell);
    // With daylight coefficients, each sky patch's factor on what a crossing adds to a learning
    // strategy's statistics (lib/sensor.h): the luminance of the sky the learning is for, per
    // patch (1 each until set: the unit sky).
    void setPatchWeights(const std::vector<float>& perPatch);

    void clear();
    // Each cell's illuminance over `paths` paths (lux): accumulators / (scale x paths).
    std::vector<double> read(std::uint64_t paths);
    // The daylight-coefficient matrices over `paths` paths, each cells x patches row-major: all
    // light, the direct light (straight from the sky through nothing but glass), and the rest (all
    // less direct, subtracted exactly in the integers: the five-phase method's indirect sun); lux
    // per path-luminance unit, so sr for a sky of unit luminance (empty without them).
    std::vector<double> readMatrices(std::uint64_t paths);

private:
    void upload(ocl::Context& ctx, const SensorTables& t);
    ocl::Context& ctx_;
    std::size_t cells_ = 0, patches_ = 0;
    int patchMF_ = 0;
    float fixedScale_ = 1.0f;
    std::size_t accumWords() const { return std::max<std::size_t>(cells_ * (1 + 2 * patches_), 1) * 2; }
    cl::Buffer info_, planes_, cellTable_, bucketStart_, bucketCells_, accum_, steer_;
};

}  // namespace fen
