// wavefront.cpp — the stage kernels and their loop (wavefront.h).
#include "render/wavefront.h"

#include <algorithm>
#include <chrono>

#include "cl/launch.h"

namespace fen {

Wavefront::Wavefront(ocl::Context& ctx, const DeviceScene& scene, EmissionStrategy& strategy,
                     Film& film, const DeviceSky& sky, const dev::DevCamera& camera, std::uint32_t pool)
    : ctx_(ctx), strategy_(strategy), film_(film), pool_(pool)
{
    paramsBuf_ = ctx.buffer(CL_MEM_READ_ONLY, sizeof(dev::RenderParams), "render parameters");
    counters_ = ctx.buffer(CL_MEM_READ_WRITE, FEN_CTR_COUNT * 8, "counters");
    paths_ = ctx.buffer(CL_MEM_READ_WRITE, std::size_t{pool} * sizeof(dev::PathState), "path pool");
    hits_ = ctx.buffer(CL_MEM_READ_WRITE, std::size_t{pool} * sizeof(dev::SurfaceHit), "hits");
    connections_ = ctx.buffer(CL_MEM_READ_WRITE, std::size_t{pool} * sizeof(dev::Connection),
                              "camera connections");
    cameraBuf_ = ctx.buffer(CL_MEM_READ_ONLY, sizeof camera, "camera", &camera);

    const auto t0 = std::chrono::steady_clock::now();
    const auto defs = scene.defines();
    auto connectDefs = defs;
    if (strategy.learns())
        connectDefs.push_back("FEN_EMISSION_STATS=1");
    emit_ = cl::Kernel(ctx.program(strategy.emitProgram(), defs), "emit_paths");
    intersect_ = cl::Kernel(ctx.program("intersect.cl", defs), "intersect_paths");
    shade_ = cl::Kernel(ctx.program("shade.cl", defs), "shade_paths");
    connect_ = cl::Kernel(ctx.program("connect.cl", connectDefs), "connect_paths");
    cameraPass_ = cl::Kernel(ctx.program("camera_pass.cl", defs), "camera_pass");
    const DeviceBvh& b = scene.bvh();
    strategy.bindEmitArgs(emit_, 3);  // checks the arity: the strategy's arguments are the last
    emit_.setArg(0, paramsBuf_);
    emit_.setArg(1, counters_);
    emit_.setArg(2, paths_);
    ocl::setKernelArgs(intersect_, paths_, hits_, pool, b.nodes(), b.packets());
    ocl::setKernelArgs(shade_, paramsBuf_, paths_, hits_, scene.primMaterial(), scene.materials(),
                       cameraBuf_, connections_, counters_);
    ocl::setKernelArgs(connect_, paramsBuf_, connections_, b.nodes(), b.packets(), scene.primMaterial(),
                       scene.materials(), film.accumulators(), strategy.cellStats(), counters_);
    ocl::setKernelArgs(cameraPass_, paramsBuf_, cameraBuf_, b.nodes(), b.packets(), scene.primMaterial(),
                       scene.materials(), sky.theta, sky.phi, sky.values, film.cameraImage(), counters_);
    warmUp();
    buildSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// PoCL compiles a kernel's work-group function at its first launch: do that here, on an empty
// pool and an empty batch, so that render time is rendering.
void Wavefront::warmUp()
{
    auto& q = ctx_.queue();
    dev::RenderParams p{};
    p.pool_size = pool_;
    q.enqueueWriteBuffer(paramsBuf_, CL_FALSE, 0, sizeof p, &p);
    q.enqueueFillBuffer(paths_, cl_uchar(0), 0, std::size_t{pool_} * sizeof(dev::PathState));
    q.enqueueFillBuffer(counters_, cl_ulong(0), 0, FEN_CTR_COUNT * 8);
    for (auto* k : {&emit_, &intersect_, &shade_, &connect_})
        ocl::launch(ctx_, *k, "warm-up", pool_);
    ocl::launch(ctx_, cameraPass_, "warm-up", film_.pixels());
    q.finish();
    ctx_.stats().reset();
}

void Wavefront::beginBatch()
{
    ctx_.queue().enqueueFillBuffer(counters_, cl_ulong(0), 0, FEN_CTR_COUNT * 8);
    ctx_.queue().enqueueFillBuffer(paths_, cl_uchar(0), 0, std::size_t{pool_} * sizeof(dev::PathState));
}

void Wavefront::run(std::uint64_t base, std::uint64_t count, BatchCounts& counts,
                    const std::function<void(std::uint64_t, std::uint64_t)>& progress)
{
    auto& q = ctx_.queue();
    const std::uint64_t end = base + count;
    params_.path_end = end;
    params_.pool_size = pool_;
    q.enqueueWriteBuffer(paramsBuf_, CL_FALSE, 0, sizeof params_, &params_);
    std::uint64_t ctr[FEN_CTR_COUNT] = {};
    q.enqueueWriteBuffer(counters_, CL_TRUE, FEN_CTR_NEXT_PATH * 8, 8, &base);
    q.enqueueReadBuffer(counters_, CL_TRUE, 0, sizeof ctr, ctr);
    const std::uint64_t zero = 0;
    std::uint64_t next = base, alive = 0, emittedBefore = ctr[FEN_CTR_EMITTED];
    for (;;) {
        if (next < end)
            ocl::launch(ctx_, emit_, "emit_paths", pool_);
        ocl::launch(ctx_, intersect_, "intersect_paths", pool_);
        q.enqueueWriteBuffer(counters_, CL_FALSE, FEN_CTR_ALIVE * 8, 8, &zero);
        ocl::launch(ctx_, shade_, "shade_paths", pool_);
        ocl::launch(ctx_, connect_, "connect_paths", pool_);
        q.enqueueReadBuffer(counters_, CL_TRUE, 0, sizeof ctr, ctr);
        // Rays traced this iteration: the paths alive before it plus those that started in it
        // (a rejected candidate spends its index but starts no path).
        const std::uint64_t started = ctr[FEN_CTR_EMITTED] - emittedBefore;
        emittedBefore = ctr[FEN_CTR_EMITTED];
        counts.extensionRays += alive + started;
        const std::uint64_t paths = std::min(ctr[FEN_CTR_NEXT_PATH], end) - std::min(next, end);
        alive = ctr[FEN_CTR_ALIVE];
        next = ctr[FEN_CTR_NEXT_PATH];
        if (progress)
            progress(paths, alive + started);
        if (alive == 0 && next >= end)
            break;
    }
}

void Wavefront::endBatch(std::uint32_t batch, BatchCounts& counts)
{
    auto& q = ctx_.queue();
    params_.batch = batch;
    q.enqueueWriteBuffer(paramsBuf_, CL_FALSE, 0, sizeof params_, &params_);
    ocl::launch(ctx_, cameraPass_, "camera_pass", film_.pixels());
    std::uint64_t ctr[FEN_CTR_COUNT] = {};
    q.enqueueReadBuffer(counters_, CL_TRUE, 0, sizeof ctr, ctr);
    counts.shadowRays += ctr[FEN_CTR_SHADOW_RAYS];
    counts.cameraRays += ctr[FEN_CTR_CAMERA_RAYS];
    counts.badContributions += ctr[FEN_CTR_BAD_CONTRIBUTIONS];
    counts.overflows += ctr[FEN_CTR_OVERFLOWS];
    counts.statsOverflows += ctr[FEN_CTR_STATS_OVERFLOWS];
    counts.maxBounceCuts += ctr[FEN_CTR_MAX_DEPTH];
    counts.cameraGlassCuts += ctr[FEN_CTR_CAMERA_GLASS_CUT];
    counts.cutFlux += (static_cast<double>(ctr[FEN_CTR_CUT_FLUX_HI]) * 18446744073709551616.0 +
                       static_cast<double>(ctr[FEN_CTR_CUT_FLUX_LO])) /
                      static_cast<double>(params_.fixed_scale);
}

}  // namespace fen
