// renderer.cpp — the wavefront render loop and batch statistics (renderer.h).
#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "bench/bench.h"
#include "cl/launch.h"
#include "render/camera_setup.h"
#include "shared/fen_render.h"
#include "util/error.h"

namespace fen {

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0)
{
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string millions(double v)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1fM", v * 1e-6);
    return buf;
}

}  // namespace

EmissionMethod parseEmissionMethod(const std::string& s)
{
    if (s == "uniform")
        return EmissionMethod::Uniform;
    if (s == "portal")
        return EmissionMethod::Portal;
    throw Error(cat("--method '", s, "': expected uniform or portal"));
}

struct Renderer::Impl {
    ocl::Context& ctx;
    RenderSettings settings;
    int width, height;
    DeviceScene scene;
    SkyTables sky;
    EmissionSetup emission;
    std::optional<PortalEmission> portal;
    dev::DevCamera camera;
    dev::RenderParams params{};
    std::uint32_t pool;

    cl::Buffer paramsBuf, counters, paths, hits, connections, accum, cameraOut, cameraBuf;
    cl::Buffer skyTheta, skyPhi, skyValues, skyFactor, sourceAlias;
    cl::Buffer portalGroups, portalRange, portalCdf, portalVertices;
    std::unique_ptr<DeviceBvh> portalBvh;
    cl::Kernel emit, intersect, shade, connect, cameraPass;
    double kernelBuildSeconds = 0.0;

    // Progress reporting across batches.
    std::uint64_t pathsDone = 0, pathsTotal = 0, raysDone = 0;
    Clock::time_point start, lastProgress;
    double budgetSeconds = 0.0;

    Impl(ocl::Context& c, const Scene& s, const std::optional<Goniogram>& g, const CameraSpec& cam,
         int w, int h, const RenderSettings& st)
        : ctx(c), settings(st), width(w), height(h),
          scene(c, s, st.bvhWidth > 0 ? st.bvhWidth : defaultBvhWidth(c.info().isGpu())),
          sky(makeSkyTables(g)), emission(setupUniformEmission(s, sky)),
          camera(makeDevCamera(cam, w, h))
    {
        // CPU: a pool whose path states, hits and connections (144 B a slot) fit in the last-level
        // cache -- every stage streams through all of it (measured on the default room: 2^16
        // slots 2.7 s, 2^19 slots 3.6 s). GPU: enough slots to fill the device.
        pool = st.poolSize > 0 ? st.poolSize : (c.info().isGpu() ? (1u << 21) : (1u << 16));
        params.seed = st.seed;
        params.max_depth = static_cast<std::uint32_t>(st.maxBounces);
        params.pool_size = pool;
        params.camera_spp = static_cast<std::uint32_t>(st.cameraSpp);
        const glm::dvec3 sd = s.sun.travelDirection;
        params.sun_dir = {static_cast<float>(sd.x), static_cast<float>(sd.y), static_cast<float>(sd.z),
                          static_cast<float>(std::cos(s.sun.angularRadiusRad))};
        fillEmissionParams(emission, sky, params);
        const IntegerCdf* sources = &emission.sources;
        const std::vector<float>* factor = &emission.skyFactor;
        if (st.method == EmissionMethod::Portal) {
            portal = setupPortalEmission(s, sky, g, st.portals, scene.bvh().width());
            sources = &portal->sources;
            factor = &portal->skyFactor;
            fillPortalParams(*portal, st.overlap, params);
        }

        paramsBuf = c.buffer(CL_MEM_READ_ONLY, sizeof params, "render parameters");
        counters = c.buffer(CL_MEM_READ_WRITE, FEN_CTR_COUNT * 8, "counters");
        paths = c.buffer(CL_MEM_READ_WRITE, std::size_t{pool} * sizeof(dev::PathState), "path pool");
        hits = c.buffer(CL_MEM_READ_WRITE, std::size_t{pool} * sizeof(dev::SurfaceHit), "hits");
        connections = c.buffer(CL_MEM_READ_WRITE, std::size_t{pool} * sizeof(dev::Connection),
                               "camera connections");
        const std::size_t px = static_cast<std::size_t>(w) * h;
        accum = c.buffer(CL_MEM_READ_WRITE, px * 6 * 8, "pixel accumulators");
        cameraOut = c.buffer(CL_MEM_READ_WRITE, px * 16, "camera-pass image");
        cameraBuf = c.buffer(CL_MEM_READ_ONLY, sizeof camera, "camera", &camera);
        skyTheta = c.buffer(CL_MEM_READ_ONLY, sky.theta.size() * 4, "sky nodes", sky.theta.data());
        skyPhi = c.buffer(CL_MEM_READ_ONLY, sky.phi.size() * 4, "sky nodes", sky.phi.data());
        skyValues = c.buffer(CL_MEM_READ_ONLY, sky.values.size() * 4, "sky luminances", sky.values.data());
        skyFactor = c.buffer(CL_MEM_READ_ONLY, factor->size() * 4, "sky weights", factor->data());
        sourceAlias = c.buffer(CL_MEM_READ_ONLY, sources->alias.size() * 4, "source table",
                               sources->alias.data());

        const auto t0 = Clock::now();
        const auto defs = scene.defines();
        if (portal)
            emit = cl::Kernel(c.program("emit_portal.cl", defs), "emit_portal_paths");
        else
            emit = cl::Kernel(c.program("emit.cl", defs), "emit_paths");
        intersect = cl::Kernel(c.program("intersect.cl", defs), "intersect_paths");
        shade = cl::Kernel(c.program("shade.cl", defs), "shade_paths");
        connect = cl::Kernel(c.program("connect.cl", defs), "connect_paths");
        cameraPass = cl::Kernel(c.program("camera_pass.cl", defs), "camera_pass");
        const DeviceBvh& b = scene.bvh();
        if (portal) {
            portalGroups = c.buffer(CL_MEM_READ_ONLY, portal->groups.size() * 16, "portal groups",
                                    portal->groups.data());
            portalRange = c.buffer(CL_MEM_READ_ONLY, portal->groupRange.size() * 4, "portal groups",
                                   portal->groupRange.data());
            portalCdf = c.buffer(CL_MEM_READ_ONLY, portal->triangleCdf.size() * 8,
                                 "portal triangle table", portal->triangleCdf.data());
            portalVertices = c.buffer(CL_MEM_READ_ONLY, portal->vertices.size() * 16,
                                      "portal triangles", portal->vertices.data());
            portalBvh = std::make_unique<DeviceBvh>(c, portal->bvh);
            ocl::setKernelArgs(emit, paramsBuf, counters, paths, skyTheta, skyPhi, skyValues,
                               skyFactor, sourceAlias, portalGroups, portalRange,
                               portalCdf, portalVertices, portalBvh->nodes(), portalBvh->packets());
        } else {
            ocl::setKernelArgs(emit, paramsBuf, counters, paths, skyTheta, skyPhi, skyValues,
                               skyFactor, sourceAlias);
        }
        ocl::setKernelArgs(intersect, paths, hits, pool, b.nodes(), b.packets());
        ocl::setKernelArgs(shade, paramsBuf, paths, hits, scene.primMaterial(), scene.materials(),
                           cameraBuf, connections, counters);
        ocl::setKernelArgs(connect, paramsBuf, connections, b.nodes(), b.packets(), scene.primMaterial(),
                           scene.materials(), accum, counters);
        ocl::setKernelArgs(cameraPass, paramsBuf, cameraBuf, b.nodes(), b.packets(), scene.primMaterial(),
                           scene.materials(), skyTheta, skyPhi, skyValues, cameraOut, counters);
        warmUp();
        kernelBuildSeconds = since(t0);
    }

    // PoCL compiles a kernel's work-group function at its first launch: do that here, on an
    // empty pool and an empty batch, so that render time is rendering.
    void warmUp()
    {
        auto& q = ctx.queue();
        dev::RenderParams p = params;
        p.path_end = 0;
        p.camera_spp = 0;
        q.enqueueWriteBuffer(paramsBuf, CL_FALSE, 0, sizeof p, &p);
        q.enqueueFillBuffer(paths, cl_uchar(0), 0, std::size_t{pool} * sizeof(dev::PathState));
        q.enqueueFillBuffer(counters, cl_ulong(0), 0, FEN_CTR_COUNT * 8);
        for (auto* k : {&emit, &intersect, &shade, &connect})
            ocl::launch(ctx, *k, "warm-up", pool);
        ocl::launch(ctx, cameraPass, "warm-up", static_cast<std::size_t>(width) * height);
        q.finish();
        ctx.stats().reset();
    }

    void progress(bool force)
    {
        if (!settings.progress)
            return;
        if (!force && std::chrono::duration<double>(Clock::now() - lastProgress).count() < 0.5)
            return;
        lastProgress = Clock::now();
        const double t = since(start);
        const double rate = t > 0.0 ? pathsDone / t : 0.0;
        double eta = 0.0;
        if (budgetSeconds > 0.0)
            eta = std::max(0.0, budgetSeconds - t);
        else if (rate > 0.0)
            eta = (pathsTotal - pathsDone) / rate;
        const std::string done = millions(static_cast<double>(pathsDone));
        const std::string of = budgetSeconds > 0.0 ? "" : "/" + millions(static_cast<double>(pathsTotal));
        std::fprintf(stderr, "\rpaths %s%s  %.2f Mpaths/s  %.2f Mrays/s  %.0f s left   ", done.c_str(),
                     of.c_str(), rate * 1e-6, t > 0.0 ? raysDone / t * 1e-6 : 0.0, eta);
        std::fflush(stderr);
    }

    // Runs paths [base, base + count) and returns the batch's image (rgb per pixel, doubles).
    std::vector<double> runBatch(std::uint64_t base, std::uint64_t count, std::uint32_t batch,
                                 RenderResult& r)
    {
        auto& q = ctx.queue();
        const std::uint64_t end = base + count;
        params.path_end = end;
        params.batch = batch;
        // 2^40 units per reference luminance: contributions down to 1e-12 of it keep 1e-6
        // relative precision, and 2^127 units hold any plausible sum (lib/accumulate.h).
        params.fixed_scale = static_cast<float>(std::ldexp(1.0, 40) / emission.referenceLuminance_cd_m2);
        q.enqueueWriteBuffer(paramsBuf, CL_FALSE, 0, sizeof params, &params);
        std::uint64_t ctr[FEN_CTR_COUNT] = {};
        ctr[FEN_CTR_NEXT_PATH] = base;
        q.enqueueWriteBuffer(counters, CL_TRUE, 0, sizeof ctr, ctr);
        q.enqueueFillBuffer(paths, cl_uchar(0), 0, std::size_t{pool} * sizeof(dev::PathState));
        q.enqueueFillBuffer(accum, cl_ulong(0), 0, static_cast<std::size_t>(width) * height * 48);

        const std::uint64_t zero = 0;
        std::uint64_t next = base, alive = 0, emittedBefore = 0;
        for (;;) {
            if (next < end)
                ocl::launch(ctx, emit, "emit_paths", pool);
            ocl::launch(ctx, intersect, "intersect_paths", pool);
            q.enqueueWriteBuffer(counters, CL_FALSE, FEN_CTR_ALIVE * 8, 8, &zero);
            ocl::launch(ctx, shade, "shade_paths", pool);
            ocl::launch(ctx, connect, "connect_paths", pool);
            q.enqueueReadBuffer(counters, CL_TRUE, 0, sizeof ctr, ctr);
            // Rays traced this iteration: the paths alive before it plus those that started in it
            // (a rejected portal candidate spends its index but starts no path).
            const std::uint64_t started = ctr[FEN_CTR_EMITTED] - emittedBefore;
            emittedBefore = ctr[FEN_CTR_EMITTED];
            r.extensionRays += alive + started;
            raysDone += alive + started;
            pathsDone += std::min<std::uint64_t>(ctr[FEN_CTR_NEXT_PATH], end) - std::min(next, end);
            alive = ctr[FEN_CTR_ALIVE];
            next = ctr[FEN_CTR_NEXT_PATH];
            progress(false);
            if (alive == 0 && next >= end)
                break;
        }
        ocl::launch(ctx, cameraPass, "camera_pass", static_cast<std::size_t>(width) * height);
        q.enqueueReadBuffer(counters, CL_TRUE, 0, sizeof ctr, ctr);
        r.shadowRays += ctr[FEN_CTR_SHADOW_RAYS];
        raysDone += ctr[FEN_CTR_SHADOW_RAYS];
        r.cameraRays += ctr[FEN_CTR_CAMERA_RAYS];
        r.badContributions += ctr[FEN_CTR_BAD_CONTRIBUTIONS];
        r.overflows += ctr[FEN_CTR_OVERFLOWS];
        r.maxBounceCuts += ctr[FEN_CTR_MAX_DEPTH];
        r.cameraGlassCuts += ctr[FEN_CTR_CAMERA_GLASS_CUT];

        const std::size_t px = static_cast<std::size_t>(width) * height;
        std::vector<std::uint64_t> acc(px * 6);
        std::vector<float> cam(px * 4);
        q.enqueueReadBuffer(accum, CL_FALSE, 0, acc.size() * 8, acc.data());
        q.enqueueReadBuffer(cameraOut, CL_TRUE, 0, cam.size() * 4, cam.data());
        std::vector<double> img(px * 3);
        const double toValue = 1.0 / (static_cast<double>(params.fixed_scale) * static_cast<double>(count));
        for (std::size_t p = 0; p < px; ++p)
            for (int c = 0; c < 3; ++c)
                img[3 * p + c] = (static_cast<double>(acc[6 * p + 2 * c + 1]) * 18446744073709551616.0 +
                                  static_cast<double>(acc[6 * p + 2 * c])) *
                                     toValue +
                                 cam[4 * p + c];
        return img;
    }

    RenderResult render()
    {
        RenderResult r;
        r.bvhSeconds = scene.bvhBuildSeconds();
        r.kernelBuildSeconds = kernelBuildSeconds;
        r.bvhWidth = scene.bvh().width();
        r.poolSize = pool;
        r.emission = emission;
        r.method = settings.method;
        if (portal) {
            r.portalNodes = portal->portals.nodes;
            r.portalTriangles = portal->portals.triangles.size();
            r.portalGroups = portal->portals.groups.size();
            r.portalSunFlux_lm = portal->sunFlux_lm;
            r.portalSkyFlux_lm = portal->skyFlux_lm;
            r.portalPrecomputeSeconds = portal->precomputeSeconds;
        }
        const std::size_t px = static_cast<std::size_t>(width) * height;
        const int batches = std::max(2, settings.batches);

        start = lastProgress = Clock::now();
        std::uint64_t perBatch = 0;
        std::uint64_t base = 0;
        if (settings.paths > 0) {
            perBatch = std::max<std::uint64_t>(1, settings.paths / static_cast<std::uint64_t>(batches));
            pathsTotal = perBatch * static_cast<std::uint64_t>(batches);
        } else {
            // Calibration, not counted: batches doubling from four pool-fulls until one lasts
            // min(1 s, 2 % of the budget), long enough to measure the path rate with the
            // per-batch overheads in it.
            budgetSeconds = settings.timeSeconds;
            RenderResult scratch;
            std::uint64_t cal = std::uint64_t{pool} * 4;
            const double enough = std::min(1.0, 0.02 * settings.timeSeconds);
            const auto c0 = Clock::now();
            double last = 0.0;
            for (;;) {
                const auto t0 = Clock::now();
                runBatch(base, cal, 0xFFFFFFFFu, scratch);
                last = since(t0);
                base += cal;
                if (last >= enough || since(c0) >= 0.1 * settings.timeSeconds)
                    break;
                cal *= 2;
            }
            r.calibrationSeconds = since(c0);
            const double rate = cal / std::max(last, 1e-6);
            const double left = std::max(0.0, settings.timeSeconds - r.calibrationSeconds);
            perBatch = static_cast<std::uint64_t>(
                std::clamp(rate * left / batches, static_cast<double>(pool), 1e15));
            pathsDone = 0;
            raysDone = 0;
            start = Clock::now();
        }

        std::vector<double> sum(px * 3, 0.0), sumY2(px, 0.0);
        r.roiBatchMeans.assign(settings.rois.size(), {});
        const auto t0 = Clock::now();
        int done = 0;
        for (;;) {
            if (settings.paths > 0 && done == batches)
                break;
            if (settings.paths == 0 && done >= 2) {
                const double elapsed = r.calibrationSeconds + since(t0);
                const double perBatchSeconds = since(t0) / done;
                if (elapsed + perBatchSeconds > settings.timeSeconds)
                    break;
            }
            const std::vector<double> img = runBatch(base, perBatch, static_cast<std::uint32_t>(done), r);
            base += perBatch;
            for (std::size_t p = 0; p < px; ++p) {
                for (int c = 0; c < 3; ++c)
                    sum[3 * p + c] += img[3 * p + c];
                const double y = luminance(img[3 * p], img[3 * p + 1], img[3 * p + 2]);
                sumY2[p] += y * y;
            }
            for (std::size_t k = 0; k < settings.rois.size(); ++k) {
                const Roi& roi = settings.rois[k];
                double m = 0.0;
                for (int y = roi.y0; y < roi.y1; ++y)
                    for (int x = roi.x0; x < roi.x1; ++x) {
                        const std::size_t p = static_cast<std::size_t>(y) * width + x;
                        m += luminance(img[3 * p], img[3 * p + 1], img[3 * p + 2]);
                    }
                r.roiBatchMeans[k].push_back(m / static_cast<double>(roi.pixels()));
            }
            ++done;
        }
        r.renderSeconds = since(t0);
        progress(true);
        if (settings.progress)
            std::fprintf(stderr, "\n");

        r.batches = done;
        r.pathsPerBatch = perBatch;
        r.paths = perBatch * static_cast<std::uint64_t>(done);
        r.image = Image(width, height);
        r.stdErrLuminance.assign(px, 0.0);
        const double B = done;
        for (std::size_t p = 0; p < px; ++p) {
            for (int c = 0; c < 3; ++c)
                r.image.rgb[3 * p + c] = static_cast<float>(sum[3 * p + c] / B);
            const double meanY = luminance(sum[3 * p], sum[3 * p + 1], sum[3 * p + 2]) / B;
            const double var = std::max(0.0, (sumY2[p] - B * meanY * meanY) / (B - 1.0));
            r.stdErrLuminance[p] = std::sqrt(var / B);
        }
        r.kernels = ctx.stats().entries();
        return r;
    }
};

double RenderResult::roiMean(std::size_t k) const
{
    const auto& v = roiBatchMeans.at(k);
    double s = 0.0;
    for (double x : v)
        s += x;
    return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

double RenderResult::roiMeanStdErr(std::size_t k) const
{
    const auto& v = roiBatchMeans.at(k);
    if (v.size() < 2)
        return 0.0;
    const double m = roiMean(k);
    double ss = 0.0;
    for (double x : v)
        ss += (x - m) * (x - m);
    return std::sqrt(ss / static_cast<double>(v.size() - 1) / static_cast<double>(v.size()));
}

Renderer::Renderer(ocl::Context& ctx, const Scene& scene, const std::optional<Goniogram>& sky,
                   const CameraSpec& camera, int width, int height, const RenderSettings& settings)
{
    if (settings.paths == 0 && !(settings.timeSeconds > 0.0))
        throw Error("render: give --paths N or --time SECONDS");
    if (settings.batches < 2)
        throw Error(cat("--batches ", settings.batches, " must be at least 2 (the noise estimate "
                        "compares batches)"));
    if (settings.maxBounces < 1)
        throw Error(cat("--max-bounces ", settings.maxBounces, " must be at least 1"));
    if (settings.cameraSpp < 1 || settings.cameraSpp > 1024)
        throw Error(cat("--camera-spp ", settings.cameraSpp, " must be in 1..1024"));
    if (settings.paths == 0 && settings.timeSeconds > 1e7)
        throw Error(cat("--time ", settings.timeSeconds, " s is beyond 10^7 s (115 days)"));
    if (!ctx.info().int64Atomics)
        throw Error(cat("OpenCL device ", ctx.info().label(), " lacks cl_khr_int64_base_atomics, "
                        "which the pixel accumulators need"));
    for (const Roi& roi : settings.rois)
        if (roi.x0 < 0 || roi.y0 < 0 || roi.x1 > width || roi.y1 > height || roi.x0 >= roi.x1 ||
            roi.y0 >= roi.y1)
            throw Error(cat("region [", roi.x0, ",", roi.y0, ")-[", roi.x1, ",", roi.y1,
                            ") is outside the ", width, " x ", height, " image"));
    impl_ = std::make_unique<Impl>(ctx, scene, sky, camera, width, height, settings);
}

Renderer::~Renderer() = default;

RenderResult Renderer::render() { return impl_->render(); }

}  // namespace fen
