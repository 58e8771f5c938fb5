// path_loop.h — the light-tracing stages on the device (DESIGN.md §2, §4), in either kernel form:
// the wavefront (a pool of path slots and per iteration emit -> intersect -> shade -> connect,
// kernels/*.cl) or the fused kernel (one kernel, whole paths per work-item), until a range of path
// indices is all emitted and dead; and the camera pass for the sky seen directly.
//
// The emission stage is built with the strategy's program and bound to its buffers; connect and
// shade to its statistics and first-bounce guide (emission/strategy.h EmissionKernels). Counters (shared/fen_render.h) are
// zeroed per batch and read back once per iteration; each launch is named and timed
// (Context::stats()).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "cl/context.h"
#include "emission/strategy.h"
#include "render/device_scene.h"
#include "render/film.h"
#include "sensor/device_sensors.h"
#include "shared/fen_render.h"
#include "team/team.h"

namespace fen {

// How the stages run: as the wavefront (four kernels an iteration over a pool of path slots), or
// fused (one kernel; each work-item runs whole paths: lib/fused_kernel.h). Both give bit-identical
// images; which is faster depends on the device (README "Kernels").
enum class KernelMode { Wavefront, Fused };
KernelMode parseKernelMode(const std::string& s);  // wavefront | fused
std::string kernelModeName(KernelMode m);
// The default: fused on a CPU, the wavefront on a GPU (measured: README "Kernels").
KernelMode defaultKernelMode(bool gpu);
// Path slots when --pool is not given. CPU: 2^16, whose path states, hits and connections fit in
// the last-level cache -- every stage streams through all of them (measured on the default
// room: 2^16 slots 2.7 s, 2^19 slots 3.6 s). GPU: 2^21, halved until the slots take at most a
// quarter of the device's memory. On an H200 (docs/results/gpu.md) 2^22 gave uniform 4.5 % more
// paths/s but adaptive 20-23 % fewer, so the default stays where both were measured well.
std::uint32_t defaultPoolSlots(const ocl::DeviceInfo& device);
// A path slot's device bytes over the pool's four buffers (state, hit, split state, connection),
// and the element of the largest of them: what a pool of N slots takes, and its largest buffer.
std::uint64_t poolSlotBytes();
std::uint64_t poolLargestSlotBytes();

// What a batch's counters say (summed over the iterations of the batch).
struct BatchCounts {
    std::uint64_t extensionRays = 0, shadowRays = 0, cameraRays = 0;
    std::uint64_t badContributions = 0, overflows = 0, statsOverflows = 0;
    std::uint64_t maxBounceCuts = 0, cameraGlassCuts = 0;
    std::uint64_t diffuseVertices = 0, guidedVertices = 0;  // scatters at diffuse vertices; of them, guided
    std::uint64_t splitBranches = 0, windowCulls = 0;       // branches splits made; paths windows culled
    std::uint64_t openingWalks = 0, openingWalkRays = 0;    // paths given to the openings' walks; their rays
    double cutFlux = 0.0;  // lm x paths: the flux of the paths --max-bounces cut
};

// Runs ranges of paths through the stages, in the kernel form `mode`.
class PathLoop {
public:
    // `sensors`: the cells every segment adds its flux to (an empty set: the kernels are built
    // without them); `sensorsSteer`: a learning strategy learns from them (a render with no image).
    PathLoop(ocl::Context& ctx, const DeviceScene& scene, EmissionStrategy& strategy, Film& film,
             const DeviceSensors& sensors, bool sensorsSteer, const DeviceSky& sky, const dev::DevCamera& camera, std::uint32_t pool,
             KernelMode mode = KernelMode::Wavefront);
    KernelMode mode() const { return mode_; }

    std::uint32_t pool() const { return pool_; }
    double kernelBuildSeconds() const { return buildSeconds_; }

    // Uploads the parameters for what follows (path_end is set per run).
    void setParams(const dev::RenderParams& params) { params_ = params; }
    // The lattice the emission table picks follow in the paths from here on (RenderParams
    // pick_offset, pick_step; kernels/lib/emit_source.h).
    void setPickLattice(std::uint32_t offset, std::uint32_t step)
    {
        params_.pick_offset = offset;
        params_.pick_step = step;
    }
    // The share of the paths from here on that start on the opening aim's panes (RenderParams
    // openings_share; the strategy's openingsShare(), pass by pass).
    void setOpeningsShare(double share) { params_.openings_share = static_cast<float>(share); }
    // The rays the device has counted since the batch began: shadow rays and the openings' walks'
    // (the extension rays are counted into BatchCounts by run()). A blocking read.
    std::uint64_t deviceRays();
    // Zeroes the counters: a batch starts.
    void beginBatch();
    // Runs paths [base, base + count) to the end. `progress(pathsDone, raysDone)` is called after
    // every iteration with the increments. When `abort()` turns true (checked between launches,
    // each a fraction of a second), no path starts any more and those started are run to their
    // end, so that paths [base, base + returned) are exactly the ones traced: a smaller, complete
    // set. Returns the paths run (count unless aborted). The paths' results do not depend on
    // where the launches split them.
    std::uint64_t run(std::uint64_t base, std::uint64_t count, BatchCounts& counts,
                      const std::function<void(std::uint64_t, std::uint64_t)>& progress,
                      const std::function<bool()>& abort = {});
    // The camera pass alone, its random numbers those of batch `batch` (render/camera_sampler.h's
    // pilot: a number no counted batch has); returns its rays. Zeroes the counters.
    std::uint64_t cameraPassAlone(std::uint32_t batch);
    // The camera pass of batch `batch`, then the batch's counters into `counts`. In a team
    // (team/team.h) the root alone runs the camera pass and the counters are summed over the
    // members, exactly, so that `counts` gets what one process tracing every path would count.
    void endBatch(std::uint32_t batch, BatchCounts& counts, Team& team);

private:
    void warmUp();
    // Launches the camera pass with batch `batch`'s random numbers, then reads the counters into
    // ctr[FEN_CTR_COUNT].
    void cameraPass(std::uint32_t batch, std::uint64_t* ctr);
    std::uint64_t runFused(std::uint64_t base, std::uint64_t count, BatchCounts& counts,
                           const std::function<void(std::uint64_t, std::uint64_t)>& progress,
                           const std::function<bool()>& abort);
    std::uint64_t fusedLaunch_ = std::uint64_t{1} << 16;  // paths per fused launch, sized by its time
    ocl::Context& ctx_;
    KernelMode mode_;
    std::size_t fusedItems_ = 0;
    EmissionStrategy& strategy_;
    Film& film_;
    dev::RenderParams params_{};
    std::uint32_t pool_;
    std::uint64_t extensionRays_ = 0;  // of the batch so far
    cl::Buffer paramsBuf_, counters_, paths_, splits_, hits_, connections_, cameraBuf_;
    cl::Buffer noPixelScale_;  // bound when the strategy weighs no statistics by pixel
    std::unique_ptr<FirstBounceGuide> noGuide_;  // bound (off) when the strategy has no guide
    std::unique_ptr<OpeningAim> noAim_;          // bound (off) when the strategy has no opening aim
    cl::Kernel emit_, intersect_, shade_, connect_, cameraPass_, fused_;
    double buildSeconds_ = 0.0;
};

}  // namespace fen
