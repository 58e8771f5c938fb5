// device_team.cpp — a render on several devices of one process (device_team.h).
#include "render/device_team.h"

#include <mutex>
#include <thread>

#include "cl/cl_error.h"
#include "team/thread_team.h"
#include "util/error.h"

namespace fen {

RenderResult renderOnDevices(const std::vector<ocl::Context*>& devices, const Scene& scene,
                             const std::optional<Goniogram>& sky, const CameraSpec& camera, int width, int height,
                             const RenderSettings& settings)
{
    const int n = static_cast<int>(devices.size());
    ThreadTeam team(n);
    std::vector<RenderResult> results(devices.size());
    std::mutex mutex;
    std::string firstError;  // the member that failed first: the cause; the others only followed
    const auto member = [&](int k) {
        RenderSettings s = settings;
        s.team = &team.member(k);
        if (k > 0) {
            s.progress = false;
            s.onBatch = nullptr;
            s.carry = nullptr;
            s.sceneCache = nullptr;
        }
        const std::string device = devices[static_cast<std::size_t>(k)]->info().label();
        std::string error;
        try {
            Renderer renderer(*devices[static_cast<std::size_t>(k)], scene, sky, camera, width, height, s);
            results[static_cast<std::size_t>(k)] = renderer.render();
            return;
        } catch (const cl::Error& e) {
            error = cat("OpenCL device ", device, ": ", ocl::describe(e));
        } catch (const Error& e) {
            error = e.what();
        } catch (const std::exception& e) {
            error = cat("device ", device, ": ", e.what());
        }
        {
            std::lock_guard<std::mutex> lock(mutex);
            if (firstError.empty())
                firstError = error;
        }
        team.breakTeam();
    };
    std::vector<std::thread> threads;
    for (int k = 1; k < n; ++k)
        threads.emplace_back(member, k);
    member(0);
    for (std::thread& t : threads)
        t.join();
    if (!firstError.empty())
        throw Error(firstError);
    return std::move(results[0]);
}

}  // namespace fen
