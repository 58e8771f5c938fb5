// direct_sun.h — the sun's direct light on the sensor cells, hour by hour, for an annual study
// with the sun apart from the sky (DESIGN.md §8 "The sun apart from the sky"; Radiance's
// five-phase method computes the same direct-sun matrix with its own rays).
//
// kernels/direct_sun.cl: for each cell and daylit hour, points x points rays from jittered points
// of the cell's square towards points of the sun's disc (its true position at the middle of the
// hour, 0.533 degrees across), through nothing but glass: the cell's mean direct-sun illuminance,
// in lux. Unbiased, each (cell, hour) with its own random numbers; deterministic for a seed.
// Hours whose sun gives no light (direct normal illuminance 0) cost no rays.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "cl/context.h"
#include "render/device_scene.h"
#include "sensor/sensor_set.h"

namespace fen {

// The sun's angular radius (rad): half of its 0.533 degrees.
constexpr double kSunAngularRadiusRad = 0.5 * 0.533 * 3.14159265358979323846 / 180.0;

class DirectSun {
public:
    // `towardsSun` (unit) and `normal_lux` per hour; `points` (>= 1) per side of a cell.
    DirectSun(ocl::Context& ctx, const DeviceScene& scene, const SensorSet& sensors,
              const std::vector<glm::dvec3>& towardsSun, const std::vector<double>& normal_lux, int points,
              std::uint32_t seed);

    // S for cells [first, first + count) and every hour, cell-major (lux).
    std::vector<float> cells(std::size_t first, std::size_t count);

    std::uint64_t samples() const { return samples_; }  // points^2 a cell and hour with sun, so far
    double seconds() const { return seconds_; }   // wall time of cells() so far

private:
    ocl::Context& ctx_;
    const DeviceScene& scene_;
    cl::Kernel kernel_;
    cl::Buffer cells_, hours_, params_;
    std::size_t cellCount_, hourCount_;
    std::uint64_t samplesPerCell_ = 0;  // points^2 for every hour with sun
    int points_;
    std::uint32_t seed_;
    std::uint64_t samples_ = 0;
    double seconds_ = 0.0;
};

}  // namespace fen
