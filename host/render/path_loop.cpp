// path_loop.cpp — the stage kernels and their loop, wavefront or fused (path_loop.h).
#include "render/path_loop.h"

#include <algorithm>
#include <chrono>

#include "cl/launch.h"
#include "util/fixed_point.h"

namespace fen {

KernelMode parseKernelMode(const std::string& s)
{
    if (s == "wavefront")
        return KernelMode::Wavefront;
    if (s == "fused")
        return KernelMode::Fused;
    throw Error(cat("--kernels '", printable(s, 40), "': expected wavefront or fused"));
}

std::string kernelModeName(KernelMode m) { return m == KernelMode::Fused ? "fused" : "wavefront"; }

KernelMode defaultKernelMode(bool gpu) { return gpu ? KernelMode::Wavefront : KernelMode::Fused; }

std::uint64_t poolSlotBytes()
{
    return sizeof(dev::PathState) + sizeof(dev::SurfaceHit) + sizeof(dev::SplitState) + sizeof(dev::Connection);
}

std::uint64_t poolLargestSlotBytes()
{
    return std::max({sizeof(dev::PathState), sizeof(dev::SurfaceHit), sizeof(dev::SplitState), sizeof(dev::Connection)});
}

std::uint32_t defaultPoolSlots(const ocl::DeviceInfo& device)
{
    if (!device.isGpu())
        return 1u << 16;
    const std::uint64_t slotBytes = poolSlotBytes(), largest = poolLargestSlotBytes();
    std::uint32_t slots = 1u << 21;
    while (slots > (1u << 16) && (slots * slotBytes > device.globalMemBytes / 4 ||
                                  slots * largest > device.maxAllocBytes))
        slots /= 2;
    return slots;
}

PathLoop::PathLoop(ocl::Context& ctx, const DeviceScene& scene, EmissionStrategy& strategy,
                   Film& film, const DeviceSensors& sensors, bool sensorsSteer, const DeviceSky& sky,
                   const dev::DevCamera& camera, std::uint32_t pool,
                   KernelMode mode)
    : ctx_(ctx), mode_(mode), strategy_(strategy), film_(film), pool_(pool)
{
    paramsBuf_ = ctx.buffer(CL_MEM_READ_ONLY, sizeof(dev::RenderParams), "render parameters");
    counters_ = ctx.buffer(CL_MEM_READ_WRITE, FEN_CTR_COUNT * 8, "counters");
    paths_ = ctx.buffer(CL_MEM_READ_WRITE, std::size_t{pool} * sizeof(dev::PathState), "path pool");
    hits_ = ctx.buffer(CL_MEM_READ_WRITE, std::size_t{pool} * sizeof(dev::SurfaceHit), "hits");
    splits_ = ctx.buffer(CL_MEM_READ_WRITE, std::size_t{pool} * sizeof(dev::SplitState), "split paths");
    connections_ = ctx.buffer(CL_MEM_READ_WRITE, std::size_t{pool} * sizeof(dev::Connection),
                              "camera connections");
    cameraBuf_ = ctx.buffer(CL_MEM_READ_ONLY, sizeof camera, "camera", &camera);

    const auto t0 = std::chrono::steady_clock::now();
    const auto defs = scene.defines();
    const EmissionKernels ek = strategy.kernels();
    // Daylight coefficients: the emitter tags each path with its sky patch (lib/sky_patch.h).
    auto emitDefs = defs;
    if (sensors.patchMF() > 0)
        emitDefs.push_back("FEN_SKY_PATCH_MF=" + std::to_string(sensors.patchMF()));
    if (ek.openingWalks)  // the openings' walks' code only where they run (lib/emit_kernel.h)
        emitDefs.push_back("FEN_OPENING_WALKS=1");
    auto shadeDefs = defs;
    if (sensors.any())
        shadeDefs.push_back("FEN_HAS_SENSORS=1");
    // With no image to learn from, a learning strategy learns from the sensors (lib/sensor.h).
    const bool sensorStats = sensors.any() && sensorsSteer && ek.gatherStats;
    if (sensorStats)
        shadeDefs.push_back("FEN_SENSOR_STATS=1");
    auto connectDefs = defs;
    if (ek.gatherStats)
        connectDefs.push_back("FEN_EMISSION_STATS=1");
    const cl::Buffer* pixelScale = ek.statsPixelScale;
    if (pixelScale)
        connectDefs.push_back("FEN_STATS_PIXEL_SCALE=1");
    else
        pixelScale = &(noPixelScale_ = ctx.buffer(CL_MEM_READ_ONLY, 4, "no pixel scale"));
    if (mode == KernelMode::Fused) {
        auto fusedDefs = connectDefs;
        fusedDefs.push_back("FEN_FUSED=1");
        if (ek.openingWalks)
            fusedDefs.push_back("FEN_OPENING_WALKS=1");
        if (sensors.patchMF() > 0)
            fusedDefs.push_back("FEN_SKY_PATCH_MF=" + std::to_string(sensors.patchMF()));
        if (sensors.any())
            fusedDefs.push_back("FEN_HAS_SENSORS=1");
        if (sensorStats)
            fusedDefs.push_back("FEN_SENSOR_STATS=1");
        fused_ = cl::Kernel(ctx.program(ek.emitProgram, fusedDefs), "trace_fused");
        // Enough work-items to keep every compute unit busy while the last chunks drain.
        fusedItems_ = std::size_t{std::max<cl_uint>(1, ctx.info().computeUnits)} * 16;
    }
    emit_ = cl::Kernel(ctx.program(ek.emitProgram, emitDefs), "emit_paths");
    intersect_ = cl::Kernel(ctx.program("intersect.cl", defs), "intersect_paths");
    shade_ = cl::Kernel(ctx.program("shade.cl", shadeDefs), "shade_paths");
    connect_ = cl::Kernel(ctx.program("connect.cl", connectDefs), "connect_paths");
    cameraPass_ = cl::Kernel(ctx.program("camera_pass.cl", defs), "camera_pass");
    const DeviceBvh& b = scene.bvh();
    const FirstBounceGuide* guide = ek.guide;
    if (!guide)
        guide = (noGuide_ = std::make_unique<FirstBounceGuide>(ctx, GuideOptions::off(), glm::dvec3(0.0), 1.0)).get();
    const OpeningAim* aim = ek.aim;
    if (!aim)
        aim = (noAim_ = std::make_unique<OpeningAim>(ctx, OpeningAimOptions::off(), nullptr)).get();
    // lib/emit_kernel.h: (params, counters, paths, the scene's buffers for the openings' walks, the aim),
    // then the strategy's arguments, the last
    strategy.bindEmitArgs(emit_, 10);  // checks the arity
    if (mode == KernelMode::Fused) {
        cl_uint a = 0;
        const cl::Buffer* fusedArgs[] = {&paramsBuf_, &counters_, &b.nodes(), &b.packets(),
                                         &scene.primMaterial(), &scene.materials(), &scene.primUv(),
                                         &scene.texels(), &cameraBuf_,
                                         &film.accumulators(), ek.cellStats, pixelScale,
                                         &guide->params(), &guide->tables(), &guide->stats(), &guide->windowStats(),
                                         &aim->aim(), &aim->prims(), &aim->stats(),
                                         &sensors.info(), &sensors.planes(), &sensors.cellTable(),
                                         &sensors.bucketStart(), &sensors.bucketCells(), &sensors.accumulators(),
                                         &sensors.steer()};
        for (const cl::Buffer* buf : fusedArgs)
            fused_.setArg(a++, *buf);
        strategy.bindEmitArgs(fused_, a);  // the strategy's arguments last; checks the arity
    }
    cl_uint e = 0;
    for (const cl::Buffer* buf : std::initializer_list<const cl::Buffer*>{
             &paramsBuf_, &counters_, &paths_, &b.nodes(), &b.packets(), &scene.primMaterial(), &scene.materials(),
             &scene.primUv(), &scene.texels(), &aim->aim()})
        emit_.setArg(e++, *buf);
    ocl::setKernelArgs(intersect_, paths_, hits_, pool, b.nodes(), b.packets());
    ocl::setKernelArgs(shade_, paramsBuf_, paths_, splits_, hits_, scene.primMaterial(), scene.materials(),
                       scene.primUv(), scene.texels(), cameraBuf_, connections_, guide->params(), guide->tables(),
                       guide->windowStats(), aim->aim(), aim->prims(), aim->stats(), sensors.info(), sensors.planes(), sensors.cellTable(), sensors.bucketStart(),
                       sensors.bucketCells(), sensors.accumulators(), *ek.cellStats, sensors.steer(), counters_);
    ocl::setKernelArgs(connect_, paramsBuf_, connections_, b.nodes(), b.packets(), scene.primMaterial(),
                       scene.materials(), film.accumulators(), *ek.cellStats, *pixelScale, guide->stats(),
                       guide->windowStats(), aim->stats(), counters_);
    ocl::setKernelArgs(cameraPass_, paramsBuf_, cameraBuf_, b.nodes(), b.packets(), scene.primMaterial(),
                       scene.materials(), sky.theta, sky.phi, sky.values, film.cameraSamples(), film.cameraImage(),
                       counters_);
    warmUp();
    buildSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// PoCL compiles a kernel's work-group function at its first launch: do that here, on an empty
// pool and an empty batch, so that render time is rendering.
void PathLoop::warmUp()
{
    auto& q = ctx_.queue();
    dev::RenderParams p{};
    p.pool_size = pool_;
    q.enqueueWriteBuffer(paramsBuf_, CL_FALSE, 0, sizeof p, &p);
    q.enqueueFillBuffer(paths_, cl_uchar(0), 0, std::size_t{pool_} * sizeof(dev::PathState));
    q.enqueueFillBuffer(counters_, cl_ulong(0), 0, FEN_CTR_COUNT * 8);
    for (auto* k : {&emit_, &intersect_, &shade_, &connect_})
        ocl::launch(ctx_, *k, "warm-up", pool_);
    if (mode_ == KernelMode::Fused)
        ocl::launch(ctx_, fused_, "warm-up", fusedItems_, 1);  // path_end 0: no path
    ocl::launch(ctx_, cameraPass_, "warm-up", film_.pixels());
    q.finish();
    ctx_.stats().reset();
}

void PathLoop::beginBatch()
{
    ctx_.queue().enqueueFillBuffer(counters_, cl_ulong(0), 0, FEN_CTR_COUNT * 8);
    ctx_.queue().enqueueFillBuffer(paths_, cl_uchar(0), 0, std::size_t{pool_} * sizeof(dev::PathState));
}

std::uint64_t PathLoop::deviceRays()
{
    std::uint64_t ctr[FEN_CTR_COUNT] = {};
    ctx_.queue().enqueueReadBuffer(counters_, CL_TRUE, 0, sizeof ctr, ctr);
    return ctr[FEN_CTR_SHADOW_RAYS] + ctr[FEN_CTR_OPENING_WALK_RAYS];
}

std::uint64_t PathLoop::run(std::uint64_t base, std::uint64_t count, BatchCounts& counts,
                             const std::function<void(std::uint64_t, std::uint64_t)>& progress,
                             const std::function<bool()>& abort)
{
    if (mode_ == KernelMode::Fused)
        return runFused(base, count, counts, progress, abort);
    auto& q = ctx_.queue();
    std::uint64_t end = base + count;
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
        // Stopping: no path starts any more; the paths in the pool run to their end (every index
        // below `next` was emitted or rejected, so [base, next) is a complete set).
        if (next < end && abort && abort()) {
            end = next;
            params_.path_end = end;
            q.enqueueWriteBuffer(paramsBuf_, CL_FALSE, 0, sizeof params_, &params_);
            if (alive == 0)
                break;
        }
    }
    return std::min(next, end) - base;
}

// In launches of a quarter of a second or so (the size doubles while a launch takes less than a
// tenth, halves while it takes more than half a second): progress stays live, and a stop waits
// for one launch. Paths are numbered, so where the launches split them changes no result.
std::uint64_t PathLoop::runFused(std::uint64_t base, std::uint64_t count, BatchCounts& counts,
                                 const std::function<void(std::uint64_t, std::uint64_t)>& progress,
                                 const std::function<bool()>& abort)
{
    auto& q = ctx_.queue();
    constexpr std::uint64_t kMinLaunch = std::uint64_t{1} << 12, kMaxLaunch = std::uint64_t{1} << 22;
    std::uint64_t ctr[FEN_CTR_COUNT] = {};
    q.enqueueReadBuffer(counters_, CL_TRUE, 0, sizeof ctr, ctr);
    std::uint64_t extensionBefore = ctr[FEN_CTR_EXTENSION_RAYS];
    std::uint64_t done = 0;
    while (done < count) {
        const std::uint64_t n = std::min(fusedLaunch_, count - done);
        params_.path_end = base + done + n;
        params_.pool_size = pool_;
        q.enqueueWriteBuffer(paramsBuf_, CL_FALSE, 0, sizeof params_, &params_);
        const std::uint64_t first = base + done;
        q.enqueueWriteBuffer(counters_, CL_FALSE, FEN_CTR_NEXT_PATH * 8, 8, &first);
        const auto t0 = std::chrono::steady_clock::now();
        ocl::launch(ctx_, fused_, "trace_fused", fusedItems_, 1);
        q.enqueueReadBuffer(counters_, CL_TRUE, 0, sizeof ctr, ctr);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (n == fusedLaunch_ && seconds < 0.1)
            fusedLaunch_ = std::min(kMaxLaunch, fusedLaunch_ * 2);
        else if (seconds > 0.5)
            fusedLaunch_ = std::max(kMinLaunch, fusedLaunch_ / 2);
        const std::uint64_t rays = ctr[FEN_CTR_EXTENSION_RAYS] - extensionBefore;
        extensionBefore = ctr[FEN_CTR_EXTENSION_RAYS];
        counts.extensionRays += rays;
        done += n;
        if (progress)
            progress(n, rays);
        if (done < count && abort && abort())
            break;
    }
    return done;
}

void PathLoop::cameraPass(std::uint32_t batch, std::uint64_t* ctr)
{
    auto& q = ctx_.queue();
    params_.batch = batch;
    q.enqueueWriteBuffer(paramsBuf_, CL_FALSE, 0, sizeof params_, &params_);
    ocl::launch(ctx_, cameraPass_, "camera_pass", film_.pixels());
    q.enqueueReadBuffer(counters_, CL_TRUE, 0, FEN_CTR_COUNT * 8, ctr);
}

std::uint64_t PathLoop::cameraPassAlone(std::uint32_t batch)
{
    ctx_.queue().enqueueFillBuffer(counters_, cl_ulong(0), 0, FEN_CTR_COUNT * 8);
    std::uint64_t ctr[FEN_CTR_COUNT] = {};
    cameraPass(batch, ctr);
    return ctr[FEN_CTR_CAMERA_RAYS];
}

void PathLoop::endBatch(std::uint32_t batch, BatchCounts& counts, Team& team)
{
    std::uint64_t ctr[FEN_CTR_COUNT] = {};
    if (team.root())
        cameraPass(batch, ctr);
    else
        ctx_.queue().enqueueReadBuffer(counters_, CL_TRUE, 0, FEN_CTR_COUNT * 8, ctr);
    if (team.size() > 1) {
        // every counter is a sum over paths (or camera samples); the cut flux a 128-bit one
        std::vector<U128> v;
        for (int i = 0; i < FEN_CTR_COUNT; ++i)
            if (i != FEN_CTR_CUT_FLUX_HI)
                v.push_back(i == FEN_CTR_CUT_FLUX_LO ? U128{ctr[i], ctr[i + 1]} : U128{ctr[i], 0});
        team.sum(v);
        for (int i = 0, k = 0; i < FEN_CTR_COUNT; ++i)
            if (i != FEN_CTR_CUT_FLUX_HI) {
                ctr[i] = v[static_cast<std::size_t>(k)].lo;
                if (i == FEN_CTR_CUT_FLUX_LO)
                    ctr[i + 1] = v[static_cast<std::size_t>(k)].hi;
                ++k;
            }
    }
    counts.shadowRays += ctr[FEN_CTR_SHADOW_RAYS];
    counts.cameraRays += ctr[FEN_CTR_CAMERA_RAYS];
    counts.badContributions += ctr[FEN_CTR_BAD_CONTRIBUTIONS];
    counts.overflows += ctr[FEN_CTR_OVERFLOWS];
    counts.statsOverflows += ctr[FEN_CTR_STATS_OVERFLOWS];
    counts.maxBounceCuts += ctr[FEN_CTR_MAX_DEPTH];
    counts.cameraGlassCuts += ctr[FEN_CTR_CAMERA_GLASS_CUT];
    counts.diffuseVertices += ctr[FEN_CTR_DIFFUSE_VERTICES];
    counts.guidedVertices += ctr[FEN_CTR_GUIDED_VERTICES];
    counts.splitBranches += ctr[FEN_CTR_SPLIT_BRANCHES];
    counts.windowCulls += ctr[FEN_CTR_WINDOW_CULLS];
    counts.openingWalks += ctr[FEN_CTR_OPENING_WALKS];
    counts.openingWalkRays += ctr[FEN_CTR_OPENING_WALK_RAYS];
    counts.cutFlux += fixed128(ctr + FEN_CTR_CUT_FLUX_LO) / static_cast<double>(params_.fixed_scale);
}

}  // namespace fen
