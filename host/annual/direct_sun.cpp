// direct_sun.cpp — the direct-sun pass of an annual study (direct_sun.h; kernels/direct_sun.cl).
#include "annual/direct_sun.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "cl/launch.h"
#include "shared/fen_sun.h"
#include "util/error.h"
#include "util/float4.h"

namespace fen {

DirectSun::DirectSun(ocl::Context& ctx, const DeviceScene& scene, const SensorSet& sensors,
                     const std::vector<glm::dvec3>& towardsSun, const std::vector<double>& normal_lux, int points,
                     std::uint32_t seed)
    : ctx_(ctx), scene_(scene), cellCount_(sensors.cells.size()), hourCount_(towardsSun.size()), points_(points),
      seed_(seed)
{
    if (points < 1 || normal_lux.size() != towardsSun.size())
        throw Error(cat("direct sun: ", points, " points a side, ", towardsSun.size(), " directions and ",
                        normal_lux.size(), " illuminances"));
    std::vector<dev::DevSunCell> cells(std::max<std::size_t>(cellCount_, 1));
    for (std::size_t c = 0; c < cellCount_; ++c) {
        const SensorCell& s = sensors.cells[c];
        glm::dvec3 u, v;
        sensorPlaneAxes(s.normal, &u, &v);  // the squares' axes, as the light tracer's (device_sensors.cpp)
        cells[c].centre = toFloat4(s.position, s.side_m);
        cells[c].u_axis = toFloat4(u, 0.0);
        cells[c].v_axis = toFloat4(v, 0.0);
        cells[c].normal = toFloat4(s.normal, 0.0);
    }
    std::vector<dev::DevSunHour> hours(std::max<std::size_t>(hourCount_, 1));
    for (std::size_t h = 0; h < hourCount_; ++h) {
        hours[h].dir = toFloat4(towardsSun[h], normal_lux[h]);
        samplesPerCell_ += normal_lux[h] > 0.0 ? static_cast<std::uint64_t>(points) * points : 0;
    }
    cells_ = ctx.buffer(CL_MEM_READ_ONLY, cells.size() * sizeof(dev::DevSunCell), "direct-sun cells", cells.data());
    hours_ = ctx.buffer(CL_MEM_READ_ONLY, hours.size() * sizeof(dev::DevSunHour), "direct-sun hours", hours.data());
    params_ = ctx.buffer(CL_MEM_READ_ONLY, sizeof(dev::DevSunParams), "direct-sun parameters");
    cl::Program prog = ctx.program("direct_sun.cl", scene.defines());
    kernel_ = cl::Kernel(prog, "direct_sun");
}

std::vector<float> DirectSun::cells(std::size_t first, std::size_t count)
{
    const auto t0 = std::chrono::steady_clock::now();
    if (first + count > cellCount_)
        throw Error(cat("direct sun: cells ", first, "..", first + count, " of ", cellCount_));
    std::vector<float> out(count * hourCount_);
    if (out.empty())
        return out;
    // Launches of at most 2^22 (cell, hour) items, so that none runs long on a display GPU.
    const std::size_t perLaunch = std::max<std::size_t>(1, (std::size_t{1} << 22) / hourCount_);
    cl::Buffer result = ctx_.buffer(CL_MEM_WRITE_ONLY, std::min(perLaunch, count) * hourCount_ * sizeof(float),
                                    "direct-sun illuminance");
    for (std::size_t done = 0; done < count; done += perLaunch) {
        const std::size_t n = std::min(perLaunch, count - done);
        dev::DevSunParams p{};
        p.first_cell = static_cast<std::uint32_t>(first + done);
        p.cells = static_cast<std::uint32_t>(n);
        p.hours = static_cast<std::uint32_t>(hourCount_);
        p.points = static_cast<std::uint32_t>(points_);
        p.seed = seed_;
        p.cos_radius = static_cast<float>(std::cos(kSunAngularRadiusRad));
        ctx_.queue().enqueueWriteBuffer(params_, CL_TRUE, 0, sizeof p, &p);
        ocl::setKernelArgs(kernel_, params_, cells_, hours_, scene_.bvh().nodes(), scene_.bvh().packets(),
                           scene_.primMaterial(), scene_.materials(), result);
        ocl::launch(ctx_, kernel_, "direct_sun", n * hourCount_);
        ctx_.queue().enqueueReadBuffer(result, CL_TRUE, 0, n * hourCount_ * sizeof(float), out.data() + done * hourCount_);
    }
    for (float v : out)
        if (!std::isfinite(v) || v < 0.0f)
            throw Error("internal error: a direct-sun illuminance is not finite and non-negative");
    samples_ += samplesPerCell_ * count;
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

}  // namespace fen
