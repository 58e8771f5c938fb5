// bench.cpp — `fenestra bench` (bench.h).
//
// Protocol (README "Performance (measured)"): the same rays on the same triangles for every
// tracer; one warm-up round, then `runs` rounds in which every tracer runs once, interleaved, so
// drift of a shared machine hits all alike; rates are rays / wall second around enqueue + finish
// (host side, as for Embree); the fenestra/Embree ratio is the median of per-round ratios.
// Embree runs twice per round: as it comes (its fastest), and with RTC_SCENE_FLAG_ROBUST, the
// closest it comes to the watertight traversal fenestra gives; both ratios are reported.
#include "bench/bench.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <thread>

#include <nlohmann/json.hpp>

#include "bench/embree_tracer.h"
#include "bench/room_scene.h"
#include "bvh_build.h"
#include "bvh_flat.h"
#include "cl/device.h"
#include "render/renderer.h"
#include "sky/sky_spec.h"
#include "trace/device_bvh.h"
#include "util/error.h"

namespace fen {


namespace {

using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point a, Clock::time_point b)
{
    return std::chrono::duration<double>(b - a).count();
}

struct Series {
    std::vector<double> v;
    double median() const
    {
        if (v.empty())
            return 0.0;
        std::vector<double> s = v;
        std::sort(s.begin(), s.end());
        const std::size_t n = s.size();
        return n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
    }
    double min() const { return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end()); }
    double max() const { return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()); }
    nlohmann::json json() const
    {
        return {{"median", median()}, {"min", min()}, {"max", max()}, {"runs", v}};
    }
};

struct LayoutRun {
    int width = 0;
    FlatBvh flat;
    std::unique_ptr<DeviceBvh> dev;
    std::unique_ptr<RayQueries> queries;
    double compileSeconds = 0.0;
    Series closestMrays, anyMrays, closestRatio, anyRatio;
    Series closestRobustRatio, anyRobustRatio;  // over Embree with RTC_SCENE_FLAG_ROBUST
    double closestAgree = -1.0, anyAgree = -1.0;
};

// Fraction of rays on which two closest-hit results agree: same triangle, or the same distance
// within 1e-4 relative (a tie between neighbours sharing an edge).
// The emission stage's share of a render's device time; null for the fused kernel, which runs
// emission inside its one kernel.
nlohmann::json emitShare(const RenderResult& r)
{
    if (r.kernelMode == KernelMode::Fused)
        return nullptr;
    double emit = 0.0, all = 0.0;
    for (const auto& [name, k] : r.kernels) {
        all += k.deviceSeconds;
        if (name == "emit_paths")
            emit += k.deviceSeconds;
    }
    return all > 0.0 ? nlohmann::json(emit / all) : nlohmann::json(nullptr);
}

double closestAgreement(const std::vector<dev::Hit>& a, const std::vector<dev::Hit>& b)
{
    std::size_t same = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const bool missA = a[i].prim == FEN_INVALID_ID, missB = b[i].prim == FEN_INVALID_ID;
        if (missA || missB) {
            same += missA == missB;
            continue;
        }
        same += a[i].prim == b[i].prim ||
                std::fabs(a[i].t - b[i].t) <= 1e-4f * std::max(1.0f, std::fabs(a[i].t));
    }
    return a.empty() ? 1.0 : static_cast<double>(same) / static_cast<double>(a.size());
}

double anyAgreement(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b)
{
    std::size_t same = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        same += (a[i] != 0) == (b[i] != 0);
    return a.empty() ? 1.0 : static_cast<double>(same) / static_cast<double>(a.size());
}

}  // namespace

int runBench(const BenchOptions& opt)
{
    if (opt.rays == 0 || opt.runs < 1 || opt.warmup < 0)
        throw Error("bench: --rays and --runs must be positive, --warmup non-negative");
    const int hw = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));

    BenchScene bs = benchSceneNamed(opt.scenePath);
    const std::vector<Triangle>& tris = bs.scene.triangles;

    ocl::Context ctx(ocl::selectDevice(opt.device));
    std::vector<int> widths = opt.widths;
    if (widths.empty())
        widths.push_back(defaultBvhWidth(ctx.info().isGpu()));

    // BVH build: median of three, so a cold first build does not decide the figure.
    Series buildMs;
    BinaryBvh bin;
    for (int i = 0; i < 3; ++i) {
        bin = buildBinnedSah(tris);
        buildMs.v.push_back(bin.buildSeconds * 1e3);
    }
    const double sah = sahCost(bin);
    double sweepSah = 0.0, sweepSeconds = 0.0;
    if (opt.sweepQuality) {
        const BinaryBvh sweep = buildSweepSah(tris);
        sweepSah = sahCost(sweep);
        sweepSeconds = sweep.buildSeconds;
    }

    const auto closestRays = makeClosestRays(bs, opt.rays, opt.seed);
    const auto occlusionRays = makeOcclusionSegments(bs, opt.rays, opt.seed);
    const auto n = static_cast<std::uint32_t>(opt.rays);
    cl::Buffer closestBuf = ctx.buffer(CL_MEM_READ_ONLY, n * sizeof(dev::Ray), "bench rays",
                                       closestRays.data());
    cl::Buffer occlusionBuf = ctx.buffer(CL_MEM_READ_ONLY, n * sizeof(dev::Ray), "bench segments",
                                         occlusionRays.data());
    cl::Buffer hitBuf = ctx.buffer(CL_MEM_WRITE_ONLY, n * sizeof(dev::Hit), "bench hits");
    cl::Buffer occBuf = ctx.buffer(CL_MEM_WRITE_ONLY, n * sizeof(std::uint32_t), "bench flags");

    std::vector<LayoutRun> layouts(widths.size());
    for (std::size_t i = 0; i < widths.size(); ++i) {
        LayoutRun& L = layouts[i];
        L.width = widths[i];
        L.flat = flattenBvh(bin, tris, L.width);
        L.dev = std::make_unique<DeviceBvh>(ctx, L.flat);
        // Program build plus the first launch of each kernel: PoCL compiles the work-group
        // function when a kernel is first enqueued. Both come from its cache on a second run.
        const auto t0 = Clock::now();
        L.queries = std::make_unique<RayQueries>(ctx, *L.dev);
        L.queries->closest(closestBuf, hitBuf, 1);
        L.queries->any(occlusionBuf, occBuf, 1);
        ctx.queue().finish();
        L.compileSeconds = seconds(t0, Clock::now());
    }

    // --render: the same scene rendered (the procedural ones with a window cut and lights
    // added), every round, so render rays/s and traversal rays/s come from the same run.
    std::unique_ptr<Renderer> renderer;
    std::optional<Goniogram> renderSky;
    Scene renderScene;
    Series renderMrays, renderRatio, renderPathsPerSec;
    RenderResult lastRender;
    if (opt.render) {
        renderScene = bs.scene;
        if (opt.scenePath.empty() || opt.scenePath == "room" || opt.scenePath == "spheres")
            makeRenderable(renderScene);
        if (renderScene.cameras.empty())
            throw Error(cat(renderScene.source, ": --render needs a camera in the scene"));
        renderSky = buildSky(renderScene);
        RenderSettings rs;
        rs.paths = opt.renderPaths;
        rs.timeSeconds = opt.renderPaths > 0 ? 0.0 : opt.renderSeconds;
        rs.emission.method = parseEmissionMethod(opt.renderMethod);
        if (!opt.kernels.empty())
            rs.kernels = parseKernelMode(opt.kernels);
        rs.seed = static_cast<std::uint32_t>(opt.seed);
        rs.bvhWidth = layouts.front().width;
        renderer = std::make_unique<Renderer>(ctx, renderScene, renderSky, renderScene.cameras.front(),
                                              320, 240, rs);
    }

#ifdef FEN_HAVE_EMBREE
    std::unique_ptr<EmbreeTracer> embree, embreeRobust;
    if (opt.embree) {
        embree = std::make_unique<EmbreeTracer>(tris, hw, false);
        embreeRobust = std::make_unique<EmbreeTracer>(tris, hw, true);
    }
#else
    const bool embreeMissing = opt.embree;
#endif
    Series embreeClosest, embreeAny, robustClosest, robustAny;
    // Results of each Embree scene, kept across rounds: closest()/any() resize them, and a fresh
    // vector each round would put its allocation and page faults inside the timed call.
    std::vector<dev::Hit> embreeHits, robustHits;
    std::vector<std::uint32_t> embreeOcc, robustOcc;

    auto timeDevice = [&](auto&& enqueue) {
        const auto t0 = Clock::now();
        enqueue();
        ctx.queue().finish();
        return static_cast<double>(n) / seconds(t0, Clock::now()) * 1e-6;
    };

    for (int round = 0; round < opt.warmup + opt.runs; ++round) {
        const bool counted = round >= opt.warmup;
        double eC = 0.0, eA = 0.0, rC = 0.0, rA = 0.0;
#ifdef FEN_HAVE_EMBREE
        // rays/s of one Embree scene, closest then any hit, into (c, a) and the series
        auto timeEmbree = [&](const EmbreeTracer& e, std::vector<dev::Hit>& hits, std::vector<std::uint32_t>& occ,
                              double& c, double& a, Series& cs, Series& as) {
            auto t0 = Clock::now();
            e.closest(closestRays, hits);
            c = n / seconds(t0, Clock::now()) * 1e-6;
            t0 = Clock::now();
            e.any(occlusionRays, occ);
            a = n / seconds(t0, Clock::now()) * 1e-6;
            if (counted) {
                cs.v.push_back(c);
                as.v.push_back(a);
            }
        };
        if (embree) {
            timeEmbree(*embree, embreeHits, embreeOcc, eC, eA, embreeClosest, embreeAny);
            timeEmbree(*embreeRobust, robustHits, robustOcc, rC, rA, robustClosest, robustAny);
        }
#endif
        for (auto& L : layouts) {
            const double c = timeDevice([&] { L.queries->closest(closestBuf, hitBuf, n); });
            const double a = timeDevice([&] { L.queries->any(occlusionBuf, occBuf, n); });
            if (!counted)
                continue;
            L.closestMrays.v.push_back(c);
            L.anyMrays.v.push_back(a);
            if (eC > 0.0) {
                L.closestRatio.v.push_back(c / eC);
                L.anyRatio.v.push_back(a / eA);
                L.closestRobustRatio.v.push_back(c / rC);
                L.anyRobustRatio.v.push_back(a / rA);
            }
        }
        if (renderer) {
            lastRender = renderer->render();
            const double rays = static_cast<double>(lastRender.counts.extensionRays + lastRender.counts.shadowRays);
            const double rate = rays / lastRender.renderSeconds * 1e-6;
            if (counted) {
                renderMrays.v.push_back(rate);
                renderPathsPerSec.v.push_back(lastRender.paths / lastRender.renderSeconds * 1e-6);
                renderRatio.v.push_back(rate / layouts.front().closestMrays.v.back());
            }
        }
    }
    if (!embreeHits.empty()) {
        for (auto& L : layouts) {
            std::vector<dev::Hit> hits(n);
            std::vector<std::uint32_t> occ(n);
            L.queries->closest(closestBuf, hitBuf, n);
            L.queries->any(occlusionBuf, occBuf, n);
            ctx.queue().enqueueReadBuffer(hitBuf, CL_TRUE, 0, n * sizeof(dev::Hit), hits.data());
            ctx.queue().enqueueReadBuffer(occBuf, CL_TRUE, 0, n * 4, occ.data());
            L.closestAgree = closestAgreement(hits, embreeHits);
            L.anyAgree = anyAgreement(occ, embreeOcc);
        }
    }

    if (opt.json) {
        nlohmann::json j;
        j["scene"] = {{"source", bs.scene.source},
                      {"triangles", tris.size()},
                      {"degenerate_dropped", bin.droppedDegenerate}};
        j["device"] = {{"name", ctx.info().label()},
                       {"type", ctx.info().typeName()},
                       {"compute_units", ctx.info().computeUnits}};
        j["rays"] = n;
        j["runs"] = opt.runs;
        j["warmup"] = opt.warmup;
        j["host_threads"] = hw;
        j["bvh_build"] = {{"builder", "binned SAH"}, {"ms", buildMs.json()}, {"sah_cost", sah},
                          {"depth", bin.depth}};
        if (opt.sweepQuality)
            j["bvh_build"]["full_sweep"] = {{"sah_cost", sweepSah},
                                            {"seconds", sweepSeconds},
                                            {"binned_over_sweep", sah / sweepSah}};
        for (const auto& L : layouts) {
            nlohmann::json l = {{"width", L.width},
                                {"nodes", L.flat.nodeCount},
                                {"node_bytes", L.flat.nodeBytes()},
                                {"packets", L.flat.packets.size()},
                                {"packet_bytes", L.flat.packetBytes()},
                                {"stack_bound", L.flat.stackBound},
                                {"flatten_ms", L.flat.flattenSeconds * 1e3},
                                {"kernel_build_s", L.compileSeconds},
                                {"closest_mrays_s", L.closestMrays.json()},
                                {"any_mrays_s", L.anyMrays.json()}};
            if (!L.closestRatio.v.empty()) {
                l["closest_over_embree"] = L.closestRatio.json();
                l["any_over_embree"] = L.anyRatio.json();
                l["closest_over_embree_robust"] = L.closestRobustRatio.json();
                l["any_over_embree_robust"] = L.anyRobustRatio.json();
                l["closest_agreement_with_embree"] = L.closestAgree;
                l["any_agreement_with_embree"] = L.anyAgree;
            }
            j["layouts"].push_back(l);
        }
#ifdef FEN_HAVE_EMBREE
        if (embree)
            j["embree"] = {{"version", embree->version()},
                           {"threads", hw},
                           {"build_ms", embree->buildSeconds() * 1e3},
                           {"closest_mrays_s", embreeClosest.json()},
                           {"any_mrays_s", embreeAny.json()},
                           {"robust",
                            {{"build_ms", embreeRobust->buildSeconds() * 1e3},
                             {"closest_mrays_s", robustClosest.json()},
                             {"any_mrays_s", robustAny.json()}}}};
#else
        j["embree"] = nullptr;
#endif
        if (renderer)
            j["render"] = {{"scene", renderScene.source},
                           {"paths", lastRender.paths},
                           {"seconds", lastRender.renderSeconds},
                           {"method", opt.renderMethod},
                           {"roulette_depth", lastRender.rouletteDepth},
                           {"kernel_mode", kernelModeName(lastRender.kernelMode)},
                           {"emit_share", emitShare(lastRender)},
                           {"width", 320},
                           {"height", 240},
                           {"extension_rays", lastRender.counts.extensionRays},
                           {"shadow_rays", lastRender.counts.shadowRays},
                           {"camera_rays", lastRender.counts.cameraRays},
                           {"mrays_s", renderMrays.json()},
                           {"mpaths_s", renderPathsPerSec.json()},
                           {"over_closest_traversal", renderRatio.json()}};
        std::cout << j.dump(2) << "\n";
        return 0;
    }

    std::printf("fenestra bench: %s, %zu triangles; %u rays; %d runs after %d warm-up\n",
                bs.scene.source.c_str(), tris.size(), n, opt.runs, opt.warmup);
    std::printf("device: %s (%s, %u compute units)\n", ctx.info().label().c_str(),
                ctx.info().typeName().c_str(), ctx.info().computeUnits);
    std::printf("BVH build (binned SAH, %d threads): median %.1f ms [%.1f-%.1f], SAH cost %.2f, "
                "depth %d%s\n",
                hw, buildMs.median(), buildMs.min(), buildMs.max(), sah, bin.depth,
                bin.droppedDegenerate ? cat(", ", bin.droppedDegenerate,
                                            " zero-area triangles dropped").c_str()
                                      : "");
    if (opt.sweepQuality)
        std::printf("full-sweep SAH: cost %.2f (binned/sweep = %.3f), built in %.2f s\n",
                    sweepSah, sah / sweepSah, sweepSeconds);
    std::printf("\n%-8s %9s %9s %9s %9s %6s %9s %10s\n", "layout", "nodes", "node MiB", "packets",
                "pack MiB", "stack", "flat ms", "kernel s");
    for (const auto& L : layouts)
        std::printf("bvh%-5d %9zu %9.2f %9zu %9.2f %6d %9.1f %10.2f\n", L.width, L.flat.nodeCount,
                    L.flat.nodeBytes() / 1048576.0, L.flat.packets.size(),
                    L.flat.packetBytes() / 1048576.0, L.flat.stackBound,
                    L.flat.flattenSeconds * 1e3, L.compileSeconds);
    std::printf("\n%-14s %26s %26s\n", "Mrays/s", "closest: median [min-max]",
                "any: median [min-max]");
    auto row = [](const std::string& name, const Series& c, const Series& a) {
        std::printf("%-14s %10.2f [%6.2f-%6.2f] %10.2f [%6.2f-%6.2f]\n", name.c_str(), c.median(),
                    c.min(), c.max(), a.median(), a.min(), a.max());
    };
    for (const auto& L : layouts)
        row(cat("fenestra bvh", L.width), L.closestMrays, L.anyMrays);
#ifdef FEN_HAVE_EMBREE
    if (embree) {
        row(cat("embree ", embree->version()), embreeClosest, embreeAny);
        row("embree robust", robustClosest, robustAny);
        std::printf("\nfenestra / Embree (median of per-run ratios; Embree on %d threads, "
                    "build %.1f ms)\n",
                    hw, embree->buildSeconds() * 1e3);
        for (const auto& L : layouts)
            std::printf("bvh%-5d closest %.2fx   any %.2fx   against robust Embree: closest %.2fx   any "
                        "%.2fx   (agreement with Embree: closest %.4f%%, any %.4f%%)\n",
                        L.width, L.closestRatio.median(), L.anyRatio.median(), L.closestRobustRatio.median(),
                        L.anyRobustRatio.median(), 100.0 * L.closestAgree, 100.0 * L.anyAgree);
    }
#else
    if (embreeMissing)
        std::printf("\n(Embree not found at build time: install libembree-dev and rebuild for "
                    "the comparison)\n");
#endif
    if (renderer) {
        std::printf("\nrender (%s, %s, %s kernels, %llu paths in %.1f s, 320 x 240, bvh%d): %.2f Mrays/s "
                    "[%.2f-%.2f] (extension + shadow rays; %.2f Mpaths/s)\n",
                    renderScene.source.c_str(), opt.renderMethod.c_str(), kernelModeName(lastRender.kernelMode).c_str(),
                    static_cast<unsigned long long>(lastRender.paths), lastRender.renderSeconds,
                    layouts.front().width, renderMrays.median(), renderMrays.min(), renderMrays.max(),
                    renderPathsPerSec.median());
        std::printf("render / closest-hit traversal on the same scene (median of per-run ratios): "
                    "%.2fx\n",
                    renderRatio.median());
    }
    return 0;
}

}  // namespace fen
