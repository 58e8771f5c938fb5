// renderer.cpp — the batch loop, calibration and progress (renderer.h).
#include "render/renderer.h"

#include "io/json_text.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "emission/emission_sphere.h"
#include "emission/light_levels.h"
#include "io/state_io.h"
#include "render/camera_setup.h"
#include "render/checkpoint.h"
#include "render/device_scene.h"
#include "render/film.h"
#include "render/last_batch.h"
#include "sensor/device_sensors.h"
#include "sensor/sensor_smoothing.h"
#include "shared/fen_rng.h"
#include "trace/device_bvh.h"
#include "util/error.h"
#include "util/fnv.h"

namespace fen {

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0)
{
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The settings with what they leave to the method filled in.
RenderSettings withMethodDefaults(RenderSettings s)
{
    if (!s.rouletteDepth)
        s.rouletteDepth = defaultRouletteDepth(s.emission.method);
    // The openings' share raced (the default) is off, quietly, where no walk could pay: with no
    // image (the aim, which learns from the camera, lists no pane) and in an annual study (a walk's
    // light has no sky patch; DESIGN.md §3.6). A fixed share there is the command line's error.
    if (s.noImage || s.skyPatchMF > 0)
        s.emission.adaptive.openingsAuto = false;
    return s;
}

std::string millions(double v)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1fM", v * 1e-6);
    return buf;
}

}  // namespace

// The scene on the device: from the caller's cache when it has one (a batch), else built here.
std::shared_ptr<const DeviceScene> deviceSceneFor(ocl::Context& c, const Scene& s, const RenderSettings& st, bool* reused)
{
    const int width = st.bvhWidth > 0 ? st.bvhWidth : defaultBvhWidth(c.info().isGpu());
    if (st.sceneCache)
        return st.sceneCache->get(c, s, width, reused);
    *reused = false;
    return std::make_shared<const DeviceScene>(c, s, width);
}

struct Renderer::Impl {
    ocl::Context& ctx;
    RenderSettings settings;
    Team& team;
    SharedSums sums;
    std::vector<double> shares;  // each member's share of a pass's paths: by its measured speed
    double memberSeconds = 0.0;  // this member's path-loop time and paths in the batch so far
    std::uint64_t memberPaths = 0;
    std::string deviceLabel;     // the root's device: what a checkpoint's fingerprint names
    bool sceneReused = false;
    std::shared_ptr<const DeviceScene> sceneHolder;
    const DeviceScene& scene;
    SkyTables skyTables;
    DeviceSky sky;
    Film film;
    DeviceSensors sensors;
    std::unique_ptr<EmissionStrategy> strategy;
    std::uint32_t pool;
    std::unique_ptr<PathLoop> loop;
    CameraSpec camera;
    std::uint64_t sceneHash_ = 0;  // only when checkpointing or resuming
    bool steersByPixel = false;    // the strategy wants the image so far (imageEstimate)
    std::optional<SensorStatistics> sensorStats;  // the counted batches' sensor cells, with sensors
    std::optional<SensorStatistics> dcStats;      // ... and their daylight coefficients, with skyPatchMF
    CameraSampler cameraSampler;  // the camera pass's samples per pixel
    // With no image and a relative target, the sensors steer: each cell's illuminance so far,
    // smoothed over its neighbours (so that one lucky path does not swing it), sets its factor.
    std::unique_ptr<SensorSmoother> steerSmoother;

    // Progress reporting across batches.
    std::uint64_t pathsDone = 0, pathsTotal = 0, raysDone = 0;
    Clock::time_point start, lastProgress;
    double budgetSeconds = 0.0;

    Impl(ocl::Context& c, const Scene& s, const std::optional<Goniogram>& g, const CameraSpec& cam,
         int w, int h, const RenderSettings& st)
        : ctx(c), settings(withMethodDefaults(st)), team(st.team ? *st.team : soloTeam()), sums(c, team),
          shares(static_cast<std::size_t>(team.size()), 1.0 / team.size()), deviceLabel(c.info().label()),
          sceneHolder(deviceSceneFor(c, s, st, &sceneReused)), scene(*sceneHolder),
          skyTables(makeSkyTables(g)), sky(c, skyTables),
          film(c, w, h, referenceLuminance(s, skyTables)),
          // illuminance ~ pi x luminance: the pixels' fixed-point range serves the cells too
          sensors(st.sensors && !st.sensors->empty()
                      ? DeviceSensors(c, *st.sensors, static_cast<float>(film.fixedScale() / M_PI), st.skyPatchMF)
                      : DeviceSensors(c)),
          strategy(makeEmissionStrategy(settings.emission, {c, s, skyTables, g, sky, scene.bvh().width(), film.fixedScale(), film.width(), film.height()})),
          pool(st.poolSize > 0 ? st.poolSize : defaultPoolSlots(c.info())),
          cameraSampler(film.pixels(), static_cast<std::uint32_t>(st.cameraSpp),
                        st.noImage ? CameraPassMode::Fixed : st.cameraPass)
    {
        if (sensors.patches() && !st.skyPatchWeights.empty()) {
            if (st.skyPatchWeights.size() != sensors.patches())
                throw Error(cat("internal error: ", st.skyPatchWeights.size(), " patch weights for ", sensors.patches(),
                                " patches"));
            sensors.setPatchWeights(std::vector<float>(st.skyPatchWeights.begin(), st.skyPatchWeights.end()));
        }
        film.setCameraSamples(cameraSampler.counts());
        team.broadcast(deviceLabel);
        camera = cam;
        if (!st.checkpointPath.empty() || !st.resumePath.empty() || team.size() > 1)
            sceneHash_ = sceneHash(s);
        dev::DevCamera devCam = makeDevCamera(cam, w, h);
        if (st.noImage)
            devCam.width = devCam.height = 0;  // nothing projects, the camera pass sees nothing
        loop = std::make_unique<PathLoop>(c, scene, *strategy, film, sensors, st.noImage, sky, devCam, pool,
                                          st.kernels ? *st.kernels : defaultKernelMode(c.info().isGpu()));
        dev::RenderParams p{};
        glm::dvec3 centre;
        double radius;
        emissionSphere(s, &centre, &radius);
        p.sphere = {static_cast<float>(centre.x), static_cast<float>(centre.y), static_cast<float>(centre.z),
                    static_cast<float>(radius)};
        const glm::dvec3 sd = s.sun.travelDirection;
        p.sun_dir = {static_cast<float>(sd.x), static_cast<float>(sd.y), static_cast<float>(sd.z),
                     static_cast<float>(std::cos(s.sun.angularRadiusRad))};
        p.seed = st.seed;
        p.max_depth = static_cast<std::uint32_t>(st.maxBounces);
        p.fixed_scale = film.fixedScale();
        const EmissionKernels ek = strategy->kernels();
        steersByPixel = ek.statsPixelScale != nullptr;
        if (st.noImage && sensors.any() && steersByPixel) {
            std::vector<double> sides;
            for (const SensorCell& cell : st.sensors->cells)
                sides.push_back(cell.side_m);
            std::nth_element(sides.begin(), sides.begin() + static_cast<std::ptrdiff_t>(sides.size() / 2), sides.end());
            steerSmoother = std::make_unique<SensorSmoother>(*st.sensors, 4.0 * sides[sides.size() / 2], &s);
        }
        p.stats_scale = static_cast<float>(ek.statsScale);
        p.sky_theta_nodes = skyTables.thetaNodes;
        p.sky_phi_nodes = skyTables.phiNodes;
        p.pool_size = pool;
        p.rr_depth = static_cast<std::uint32_t>(*settings.rouletteDepth);  // resolved: always set
        p.openings_share = 0.0f;  // the strategy's, set before each pass (runBatch)
        p.split_max = static_cast<std::uint32_t>(st.splitMax);
        p.split_weight = static_cast<float>(st.splitWeight * strategy->emittedFluxPerPath());
        if (!(p.split_weight > 0.0f))
            p.split_max = 1u;  // no light emitted: nothing to split
        loop->setParams(p);
        checkTeamAgrees();
    }

    // Every member must render the same thing (a node with another copy of the scene, a rank
    // started with other arguments): the root's fingerprint -- scene bytes, camera, settings --
    // against each member's own, so that a difference is an error naming it, not a hang.
    void checkTeamAgrees()
    {
        if (team.size() == 1)
            return;
        const nlohmann::json mine = fingerprint();
        std::string root = mine.dump();
        team.broadcast(root);
        const nlohmann::json theirs = nlohmann::json::parse(root);
        for (const auto& [key, value] : mine.items())
            if (!theirs.contains(key) || theirs[key] != value)
                throw Error(cat("this member's render differs from rank 0's in its ", key, ": ",
                                printable(value.dump(), 120), " here, ",
                                printable(theirs.contains(key) ? theirs[key].dump() : "nothing", 120),
                                " there (every rank must read the same scene and options)"));
    }

    bool stopping() const { return settings.stop && settings.stop->load(); }
    // A stop asked of any member, on every member (a collective: all members call it together).
    bool stopAgreed() { return team.size() > 1 ? anyMember(team, stopping()) : stopping(); }

    // This member's part [lo, hi) of paths [first, first + n): consecutive shares in rank order,
    // in proportion to `shares`. The same on every member; the last ends at first + n exactly.
    std::pair<std::uint64_t, std::uint64_t> memberRange(std::uint64_t first, std::uint64_t n) const
    {
        if (team.size() == 1)
            return {first, first + n};
        double total = 0.0, before = 0.0;
        for (std::size_t k = 0; k < shares.size(); ++k) {
            total += shares[k];
            if (static_cast<int>(k) < team.rank())
                before += shares[k];
        }
        const auto at = [&](double s) {
            return first + std::min(n, static_cast<std::uint64_t>(std::floor(static_cast<double>(n) * (s / total))));
        };
        const bool last = team.rank() == team.size() - 1;
        return {at(before), last ? first + n : at(before + shares[static_cast<std::size_t>(team.rank())])};
    }

    // After a batch: the members' shares of the next in proportion to their paths per second in
    // this one (a member that ran none keeps its share).
    void rebalance()
    {
        if (team.size() == 1)
            return;
        const double rate = memberPaths > 0 && memberSeconds > 0.0 ? static_cast<double>(memberPaths) / memberSeconds : 0.0;
        const std::vector<double> rates = team.gather(rate);
        double sum = 0.0;
        for (double r : rates)
            sum += r;
        for (std::size_t k = 0; k < rates.size(); ++k)
            if (rates[k] > 0.0 && sum > 0.0)
                shares[k] = rates[k] / sum;
        memberSeconds = 0.0;
        memberPaths = 0;
    }

    // The device buffers a pass adds to, as a team sums them after it: the strategy's statistics
    // always; the film and sensor cells (`image`) only where something reads them mid-batch -- a
    // strategy that steers by pixel -- else once, at the batch's end (the film is 93 % of a
    // 1920 x 1080 render's summed bytes: docs/results/scaling.md).
    std::vector<SummedBuffer> summedBuffers(bool image) const
    {
        std::vector<SummedBuffer> b;
        if (image)
            b = {film.summed(), sensors.summed()};
        for (const SummedBuffer& s : strategy->summedBuffers())
            b.push_back(s);
        return b;
    }

    // The root's camera-pass image, on every member's device.
    void shareCamera()
    {
        if (team.size() == 1)
            return;
        std::string bytes;
        if (team.root()) {
            const std::vector<float> cam = film.readCamera();
            bytes.assign(reinterpret_cast<const char*>(cam.data()), cam.size() * sizeof(float));
        }
        team.broadcast(bytes);
        if (!team.root()) {
            std::vector<float> cam(bytes.size() / sizeof(float));
            std::memcpy(cam.data(), bytes.data(), cam.size() * sizeof(float));
            film.writeCamera(cam);
        }
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

    // Hands a strategy that steers by pixel the image so far: the counted batches' mean, or
    // before there is one, the batch in flight after `paths` of its paths. A function of the seed
    // and settings only, so learning stays deterministic, and of the counted batches alone
    // between batches, so a resumed render sees what the uninterrupted one saw.
    void estimateImage(const BatchStatistics* stats, std::uint64_t paths)
    {
        if (!steersByPixel)
            return;
        if (steerSmoother) {
            // The sensors' relative target: a cell counts as its illuminance times the grid's
            // mean over its own (smoothed, floored at 10^-4 of the mean), as a pixel counts
            // relative to its tile's brightness (emission/adaptive_strategy.cpp).
            const std::vector<double> raw = sensorStats && sensorStats->batches() > 0 ? sensorStats->mean()
                                                                                   : sensors.read(std::max<std::uint64_t>(paths, 1));
            const std::vector<double> e = steerSmoother->apply(raw);
            double mean = 0.0;
            for (double v : e)
                mean += v / static_cast<double>(e.size());
            if (mean > 0.0) {
                std::vector<float> steer(e.size());
                for (std::size_t c = 0; c < e.size(); ++c)
                    steer[c] = static_cast<float>(mean / std::max(e[c], 1e-4 * mean));
                sensors.setSteer(steer);
            }
        }
        std::vector<double> Y(film.pixels());
        if (stats && stats->batches() > 0) {
            const Image m = stats->mean();
            for (std::size_t p = 0; p < Y.size(); ++p)
                Y[p] = luminance(m.rgb[3 * p], m.rgb[3 * p + 1], m.rgb[3 * p + 2]);
        } else {
            const std::vector<double> rgb = film.read(paths);
            for (std::size_t p = 0; p < Y.size(); ++p)
                Y[p] = luminance(rgb[3 * p], rgb[3 * p + 1], rgb[3 * p + 2]);
        }
        strategy->imageEstimate(Y);
    }

    // The emission table picks of paths [first, first + n), one run of the path loop (a batch, or a
    // learning pass within one): one sweep of a lattice over them at an offset drawn from the seed
    // and `first` (kernels/lib/emit_source.h emission_pick_bits). Per run, not per batch: a
    // learning strategy's pass must see every column of its table, as its statistics assume.
    void setPickLattice(std::uint64_t first, std::uint64_t n)
    {
        dev::RngBlock ctr{static_cast<std::uint32_t>(first), static_cast<std::uint32_t>(first >> 32), 0u,
                          FEN_RNG_PICK_LATTICE};
        const std::uint32_t offset = dev::fen_philox4x32_10(ctr, settings.seed, FEN_RNG_STREAM_PICK_LATTICE).x;
        const double step = std::ldexp(1.0, 32) / static_cast<double>(std::max<std::uint64_t>(n, 1));
        loop->setPickLattice(offset, static_cast<std::uint32_t>(std::clamp(std::round(step), 1.0, 4294967295.0)));
    }

    // The paths of the batches counted: whole ones, and a render by time's last (0: none).
    static std::uint64_t countedPaths(const LoopState& l, std::uint64_t last)
    {
        const int whole = l.done - (last > 0 ? 1 : 0);
        return l.perBatch * static_cast<std::uint64_t>(whole) + last;
    }

    // The camera pass's device seconds so far (the kernels' named timers).
    double cameraDeviceSeconds() const
    {
        double s = 0.0;
        for (const auto& [name, e] : ctx.stats().entries())
            if (name == "camera_pass")
                s += e.deviceSeconds;
        return s;
    }

    struct BatchImage {
        std::vector<double> rgb;  // per pixel
        std::vector<float> camera;  // the camera pass's output (film.h cameraImage)
        std::vector<double> sensorLux;  // per sensor cell
        std::vector<double> coefficients;  // the daylight-coefficient matrices, with skyPatchMF
        std::uint64_t paths = 0;  // traced: the batch's count, or fewer when a stop cut it short
    };

    // Runs paths [base, base + count) as one batch, in the strategy's passes, and returns its
    // image. `stats`: the counted batches so far (none while calibrating). A stop (settings.stop)
    // ends the batch within a launch: the paths begun are finished and no more start, so the
    // image is that of the fewer paths traced (BatchImage::paths).
    BatchImage runBatch(std::uint64_t base, std::uint64_t count, std::uint32_t batch, BatchCounts& counts,
                        const BatchStatistics* stats)
    {
        film.clear();
        sensors.clear();
        loop->beginBatch();
        const std::uint64_t extensionBefore = counts.extensionRays;
        const auto onIteration = [this](std::uint64_t paths, std::uint64_t rays) {
            pathsDone += paths;
            raysDone += rays;
            progress(false);
        };
        const auto abort = [this] { return stopping(); };
        std::uint64_t done = 0;
        std::uint64_t deviceSoFar = 0;  // the device's shadow and walk rays in the batch (beginBatch zeroed them)
        while (done < count) {
            const std::uint64_t n = std::min(count - done, std::max<std::uint64_t>(1, strategy->passLimit(count - done)));
            setPickLattice(base + done, n);
            loop->setOpeningsShare(strategy->openingsShare());
            const auto [lo, hi] = memberRange(base + done, n);
            sums.before(summedBuffers(steersByPixel));
            const auto t0 = Clock::now();
            const std::uint64_t passExtension = counts.extensionRays;
            std::uint64_t ran = loop->run(lo, hi - lo, counts, onIteration, abort);
            const std::uint64_t deviceNow = loop->deviceRays();
            std::uint64_t rays = counts.extensionRays - passExtension + deviceNow - deviceSoFar;
            deviceSoFar = deviceNow;
            memberSeconds += since(t0);
            memberPaths += ran;
            bool cut = ran < hi - lo;
            if (team.size() > 1) {
                // the team's paths and rays of the pass, and whether a stop cut any member's share short
                std::vector<U128> extra{{ran, 0}, {cut ? 1u : 0u, 0}, {rays, 0}};
                sums.after(extra);
                pathsDone += extra[0].lo - ran;  // the progress line counts the team's paths
                ran = extra[0].lo;
                cut = extra[1].lo != 0;
                rays = extra[2].lo;
            }
            done += ran;
            strategy->afterPaths(ran, rays, done == count || cut);
            if (cut)
                break;
            // A counted batch's end is estimated from the counted batches, batch included, by
            // the render loop: not twice.
            if (done < count || !stats)
                estimateImage(stats, done);
        }
        if (team.size() > 1 && !steersByPixel) {
            // the film and cells, cleared at the batch's start and not summed since: from zero
            sums.before({film.summed(), sensors.summed()}, true);
            std::vector<U128> none;
            sums.after(none);
        }
        const std::uint64_t shadowBefore = counts.shadowRays;
        if (team.size() > 1)  // the host counts extension rays: the team's, as the device counters
            counts.extensionRays = extensionBefore + sumOver(team, counts.extensionRays - extensionBefore);
        loop->endBatch(batch, counts, team);
        shareCamera();
        raysDone += counts.shadowRays - shadowBefore;
        BatchImage img;
        img.rgb = film.read(done, &img.camera);
        img.sensorLux = sensors.read(done);
        img.coefficients = sensors.readMatrices(done);
        img.paths = done;
        return img;
    }

    // A batch counted: into the film's and sensors' statistics, and what the camera pass learns
    // from it sets its samples for the next (`before`: the counts before the batch).
    // `pathsShare`: the batch's paths over a full batch's (below 1 for a render by time's last batch).
    void countBatch(const BatchImage& img, const BatchCounts& before, const BatchCounts& after, BatchStatistics& stats,
                    double pathsShare)
    {
        const double w = strategy->batchWeight(pathsShare);
        if (sensorStats)
            sensorStats->add(img.sensorLux, w);
        if (dcStats)
            dcStats->add(img.coefficients, w);
        if (cameraSampler.mode() == CameraPassMode::Fixed) {
            // The same samples every batch, so the camera pass is part of the batch's image (and
            // the image is the one this mode always gave, bit for bit).
            std::vector<double> whole = img.rgb;
            for (std::size_t p = 0; p < film.pixels(); ++p)
                for (int c = 0; c < 3; ++c)
                    whole[3 * p + c] += img.camera[4 * p + c];
            stats.add(whole, w);
            cameraSampler.afterBatch({}, w, 0);
            return;
        }
        stats.add(img.rgb, w);  // the light-traced part; the camera's apart, weighed by its samples
        stats.addCamera(img.camera, cameraSampler.counts());
        std::vector<double> light(film.pixels());
        for (std::size_t p = 0; p < light.size(); ++p)
            light[p] = luminance(img.rgb[3 * p], img.rgb[3 * p + 1], img.rgb[3 * p + 2]);
        cameraSampler.afterBatch(light, w, (after.extensionRays + after.shadowRays) - (before.extensionRays + before.shadowRays),
                                 pathsShare);
        film.setCameraSamples(cameraSampler.counts());
    }

    // Balanced camera sampling starts with its pilot: each pixel's own variance, from samples of
    // their own (camera_sampler.h). Not on resume: the checkpoint has it.
    void cameraPilot()
    {
        while (cameraSampler.needsPilot()) {
            // random numbers of batches no counted batch is (nor the calibration, 0xFFFFFFFF)
            std::uint64_t rays = 0;
            if (team.root())
                rays = loop->cameraPassAlone(0xFFFFFFFEu - static_cast<std::uint32_t>(cameraSampler.pilotPass()));
            shareCamera();
            rays = sumOver(team, rays);
            cameraSampler.addPilot(film.readCamera(), rays, static_cast<std::size_t>(film.width()));
            film.setCameraSamples(cameraSampler.counts());
        }
    }

    // The strategy's state, as a checkpoint holds it (between batches).
    std::string strategyState() const
    {
        StateWriter w;
        strategy->saveState(w);
        return w.bytes();
    }

    // The sensors' cells, as a hash of their positions, normals and sides (0: none).
    std::string sensorFingerprint() const
    {
        Fnv f;  // over the cells' doubles
        if (settings.sensors)
            for (const SensorCell& c : settings.sensors->cells) {
                for (int k = 0; k < 3; ++k) {
                    f.value(c.position[k]);
                    f.value(c.normal[k]);
                }
                f.value(c.side_m);
            }
        return cat(settings.sensors ? settings.sensors->cells.size() : 0, ":", hex64(f.h));
    }

    // The patch weights as a hash of their doubles ("" with none).
    std::string patchWeightsHash() const
    {
        if (settings.skyPatchWeights.empty())
            return "";
        Fnv f;
        for (double v : settings.skyPatchWeights)
            f.value(v);
        return hex64(f.h);
    }

    // What must be equal for a checkpoint to continue this render (render/checkpoint.h).
    nlohmann::json fingerprint() const
    {
        const EmissionSettings& e = settings.emission;
        const auto v3 = [](const glm::dvec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); };
        nlohmann::json rois = nlohmann::json::array();
        for (const Roi& q : settings.rois)
            rois.push_back({q.x0, q.y0, q.x1, q.y1});
        return {{"scene", hex64(sceneHash_)},
                {"camera", {{"position", v3(camera.position)}, {"forward", v3(camera.forward)},
                            {"up", v3(camera.up)}, {"yfov", camera.yfovRad}}},
                {"width", film.width()},
                {"height", film.height()},
                {"device", deviceLabel},
                {"bvh_width", scene.bvh().width()},
                {"seed", settings.seed},
                {"paths", settings.paths},
                {"time", settings.paths > 0 ? 0.0 : settings.timeSeconds},
                {"batches", settings.batches},
                {"camera_spp", settings.cameraSpp},
                {"camera_pass", cameraPassModeName(settings.cameraPass)},
                {"max_bounces", settings.maxBounces},
                {"roulette_depth", *settings.rouletteDepth},
                {"split_max", settings.splitMax},
                {"split_weight", settings.splitWeight},
                {"rois", rois},
                {"sensors", sensorFingerprint()},
                {"no_image", settings.noImage},
                // an annual study's coefficients: the sky's subdivision, and the year's patch
                // weights the learning followed (hashed)
                {"sky_patch_mf", settings.skyPatchMF},
                {"sky_patch_weights", patchWeightsHash()},
                {"method", methodName(e.method)},
                {"portals", e.portals},
                // the strategy's own settings (strategy_registry.h), after "method" so that a
                // checkpoint of another method is refused by naming it
                {"method_options", {{methodName(e.method), strategyDescriptor(e.method).fingerprint(e)}}}};
    }

    // `strategyBytes`: the strategy's state as strategyState() took it at the end of the last
    // counted batch, when it has moved on since (a batch cut short by a stop); else its state now.
    void saveCheckpoint(const LoopState& l, double renderSeconds, const RenderResult& r, const BatchStatistics& stats,
                        const std::string* strategyBytes = nullptr)
    {
        StateWriter w;
        LoopState saved = l;
        saved.renderSeconds = renderSeconds;
        saved.calibrationSeconds = r.calibrationSeconds;
        saved.counts = r.counts;
        writeLoopState(w, saved);
        stats.save(w);
        cameraSampler.save(w);
        if (sensorStats)
            sensorStats->save(w);
        if (dcStats)
            dcStats->save(w);
        if (strategyBytes)
            w.append(*strategyBytes);
        else
            strategy->saveState(w);
        w.str("carry", settings.carry ? dumpUtf8(*settings.carry) : std::string("null"));
        writeCheckpoint(settings.checkpointPath, fingerprint(), w.bytes());
    }

    void resume(LoopState& l, RenderResult& r, BatchStatistics& stats)
    {
        const std::string bytes = readCheckpoint(settings.resumePath, fingerprint());
        StateReader in(bytes, settings.resumePath);
        readLoopState(in, {settings.paths, std::max(2, settings.batches)}, &l);
        r.calibrationSeconds = l.calibrationSeconds;
        r.counts = l.counts;
        stats.load(in);
        if (stats.batches() != l.done)
            in.fail("film.batches", "does not match loop.done");
        cameraSampler.load(in);
        film.setCameraSamples(cameraSampler.counts());
        if (sensorStats) {
            sensorStats->load(in);
            if (sensorStats->batches() != l.done)
                in.fail("sensors.batches", "does not match loop.done");
        }
        if (dcStats) {
            dcStats->load(in);
            if (dcStats->batches() != l.done)
                in.fail("sensors.batches", "of the daylight coefficients does not match loop.done");
        }
        strategy->loadState(in);
        estimateImage(&stats, 0);
        const std::string carry = in.str("carry", 1u << 30);
        in.end();
        if (settings.carry) {
            *settings.carry = nlohmann::json::parse(carry, nullptr, false);
            if (settings.carry->is_discarded())
                in.fail("carry", "not JSON");
        }
        r.resumedBatches = l.done;
    }

    RenderResult render()
    {
        RenderResult r;
        r.bvhSeconds = sceneReused ? 0.0 : scene.bvhBuildSeconds();
        r.bvhReused = sceneReused;
        r.kernelBuildSeconds = loop->kernelBuildSeconds();
        r.bvhWidth = scene.bvh().width();
        r.poolSize = pool;
        r.kernelMode = loop->mode();
        r.rouletteDepth = *settings.rouletteDepth;
        r.method = strategy->method();
        const int batches = std::max(2, settings.batches);
        BatchStatistics stats(film.width(), film.height(), settings.rois);
        if (sensors.any())
            sensorStats.emplace(sensors.cells());
        if (sensors.patches())
            dcStats.emplace(3 * sensors.cells() * sensors.patches(), false);
        LoopState l;

        start = lastProgress = Clock::now();
        if (settings.paths > 0)
            pathsTotal = std::max<std::uint64_t>(1, settings.paths / static_cast<std::uint64_t>(batches)) *
                         static_cast<std::uint64_t>(batches);
        if (!settings.resumePath.empty()) {
            resume(l, r, stats);
            pathsDone = l.perBatch * static_cast<std::uint64_t>(l.done);
            budgetSeconds = settings.paths > 0 ? 0.0 : settings.timeSeconds;
        } else if (settings.paths > 0) {
            const auto p0 = Clock::now();
            cameraPilot();
            l.renderSeconds += since(p0);  // part of the render
            l.perBatch = std::max<std::uint64_t>(1, settings.paths / static_cast<std::uint64_t>(batches));
        } else {
            // Calibration, not counted: batches doubling from four pool-fulls until one lasts
            // min(1 s, 2 % of the budget), long enough to measure the path rate with the
            // per-batch overheads in it, and the strategy has learned what it wants to before the
            // counted batches (the openings' race: host/emission/openings_race.h), while the
            // calibration is under a tenth of the budget (checked after each batch).
            budgetSeconds = settings.timeSeconds;
            BatchCounts scratch;
            std::uint64_t cal = std::uint64_t{pool} * 4;
            const double enough = std::min(1.0, 0.02 * settings.timeSeconds);
            const auto c0 = Clock::now();
            cameraPilot();  // timed with the calibration: before it, so that it measures what batches cost
            double last = 0.0;
            for (;;) {
                const auto t0 = Clock::now();
                const std::uint64_t ran = runBatch(l.base, cal, 0xFFFFFFFFu, scratch, nullptr).paths;
                last = fromRoot(team, since(t0));  // a team goes by the root's clock
                rebalance();
                l.base += ran;
                if (ran < cal) {  // stopped: the rate of what ran is as good a guess as any
                    cal = std::max<std::uint64_t>(ran, 1);
                    break;
                }
                const bool measured = last >= enough && !strategy->learningPending();
                if (fromRoot(team, measured || since(c0) >= 0.1 * settings.timeSeconds) || stopAgreed())
                    break;
                cal *= 2;
            }
            r.calibrationSeconds = fromRoot(team, since(c0));
            const double rate = cal / std::max(last, 1e-6);
            const double left = std::max(0.0, settings.timeSeconds - r.calibrationSeconds);
            l.perBatch = static_cast<std::uint64_t>(
                std::clamp(rate * left / batches, static_cast<double>(pool), 1e15));
            pathsDone = 0;
            raysDone = 0;
            start = Clock::now();
        }

        const auto t0 = Clock::now();
        const auto renderSeconds = [&] { return l.renderSeconds + since(t0); };
        const bool checkpointing = !settings.checkpointPath.empty();
        auto lastCheckpoint = Clock::now();
        int savedAt = l.done;
        std::string counted;  // the strategy's state after the last counted batch (checkpointing)
        // A checkpoint that cannot be written ends the render, after the batches done are written.
        // In a team the root writes it, and everyone learns whether it could.
        const auto checkpoint = [&](const std::string* strategyBytes) {
            bool ok = true;
            if (team.root()) {
                try {
                    saveCheckpoint(l, renderSeconds(), r, stats, strategyBytes);
                } catch (const Error& e) {
                    r.checkpointError = e.what();
                    ok = false;
                }
            }
            if (!fromRoot(team, ok)) {
                if (r.checkpointError.empty())
                    r.checkpointError = "the root could not write the checkpoint";
                return false;
            }
            lastCheckpoint = Clock::now();
            savedAt = l.done;
            ++r.checkpoints;
            return true;
        };
        bool partial = false;  // the one batch counted was cut short by a stop
        bool dropped = false;  // a batch cut short by a stop was dropped: the strategy moved on
        std::uint64_t last = 0;  // a render by time's last batch, fitted to the time left (last_batch.h)
        const int doneBefore = l.done;
        const double cameraBefore = cameraDeviceSeconds();
        double batchSeconds = 0.0;  // the last whole batch's, this process's
        // Not where a checkpoint is kept (its loop state has equal batches), nor with the fixed
        // camera pass, which folds a whole batch's camera samples into a batch the weights take as
        // a smaller one (the noise estimate would then be low).
        const bool fitLast = settings.paths == 0 && !checkpointing &&
                             (settings.noImage || cameraSampler.mode() != CameraPassMode::Fixed);
        for (;;) {
            if (settings.paths > 0 && l.done >= batches)
                break;
            if (l.done >= 1 && stopAgreed()) {
                r.interrupted = true;
                break;
            }
            if (settings.paths == 0 && l.done >= 2) {
                const double elapsed = r.calibrationSeconds + renderSeconds();
                const double perBatchSeconds = renderSeconds() / l.done;
                if (fromRoot(team, elapsed + perBatchSeconds > settings.timeSeconds)) {  // the root's clock
                    // Sized by the slower of the mean batch and the last (the rate drifts), with the
                    // camera pass's time a batch as measured here: none before this process's first.
                    const int here = l.done - doneBefore;
                    if (fitLast && here > 0)
                        last = LastBatch::paths(l.perBatch, std::max(perBatchSeconds, batchSeconds),
                                                (cameraDeviceSeconds() - cameraBefore) / here,
                                                settings.timeSeconds - elapsed);
                    last = static_cast<std::uint64_t>(fromRoot(team, static_cast<double>(last)));
                    if (last == 0)
                        break;
                }
            }
            if (checkpointing)
                counted = strategyState();
            const BatchCounts countsBefore = r.counts;
            const std::uint64_t count = last > 0 ? last : l.perBatch;
            const auto batchStart = Clock::now();
            const BatchImage img = runBatch(l.base, count, static_cast<std::uint32_t>(l.done), r.counts, &stats);
            if (img.paths < count) {
                // Stopped inside the batch. With batches done, the image is theirs and this one is
                // dropped (its counts too; a checkpoint gets the strategy as they left it); with
                // none, the paths it traced are the image: one smaller batch, and no checkpoint.
                r.interrupted = true;
                if (l.done >= 1) {
                    r.counts = countsBefore;
                    dropped = true;
                    last = 0;  // not counted
                    break;
                }
                countBatch(img, countsBefore, r.counts, stats, 1.0);  // the only batch: its weight is moot
                l.base += img.paths;
                l.perBatch = img.paths;
                ++l.done;
                partial = true;
                break;
            }
            countBatch(img, countsBefore, r.counts, stats,
                       last > 0 ? static_cast<double>(last) / static_cast<double>(l.perBatch) : 1.0);
            estimateImage(&stats, 0);
            rebalance();
            batchSeconds = since(batchStart);
            l.base += count;
            ++l.done;
            if (settings.onBatch)
                settings.onBatch({l.done, countedPaths(l, last), r.calibrationSeconds + renderSeconds(), &stats});
            if (last > 0)
                break;  // the time is up
            const bool due = settings.checkpointBatches > 0
                                 ? (l.done - savedAt) >= settings.checkpointBatches
                                 : since(lastCheckpoint) >= settings.checkpointSeconds;
            if (checkpointing && fromRoot(team, due || stopping()) && !checkpoint(nullptr)) {
                r.interrupted = true;
                break;
            }
        }
        if (checkpointing && r.interrupted && !partial && savedAt != l.done && r.checkpointError.empty())
            checkpoint(dropped ? &counted : nullptr);
        r.renderSeconds = renderSeconds();
        progress(true);
        if (settings.progress)
            std::fprintf(stderr, "\n");

        r.batches = l.done;
        r.pathsPerBatch = l.perBatch;
        r.lastBatchPaths = last > 0 ? last : l.perBatch;
        r.paths = countedPaths(l, last);
        r.image = stats.mean();
        r.stdErrLuminance = stats.stdErrLuminance();
        r.roiBatchMeans = stats.roiBatchMeans();
        r.roiCamera.clear();
        for (std::size_t k = 0; k < settings.rois.size(); ++k)
            r.roiCamera.push_back(stats.roiCamera(k));
        r.batchWeights = stats.weights();
        r.sensors = sensorStats;
        r.daylightCoefficients = dcStats;
        r.emission = strategy->report();
        r.emissionWarnings = strategy->warnings();
        r.emittedFluxPerPath = strategy->emittedFluxPerPath();
        r.kernels = ctx.stats().entries();
        if (team.size() > 1) {
            r.team = sums.report();
            r.team["members"] = team.size();
            r.team["kind"] = team.describe();
            r.team["shares"] = shares;
        }
        double deviceSeconds = 0.0;
        for (const auto& [name, e] : r.kernels)
            deviceSeconds += e.deviceSeconds;
        const double cameraSeconds = cameraDeviceSeconds();
        r.cameraSamplesPerPixel = static_cast<double>(cameraSampler.samplesTotal()) /
                                  static_cast<double>(std::max<std::size_t>(film.pixels(), 1));
        r.cameraPass = {{"mode", cameraPassModeName(cameraSampler.mode())},
                        {"floor_samples", settings.cameraSpp},
                        {"samples", cameraSampler.samplesTotal()},
                        {"samples_next_batch", cameraSampler.samplesPerBatch()},
                        {"max_samples_per_pixel", cameraSampler.maxCount()},
                        {"pixels_above_floor", cameraSampler.pixelsAboveFloor()},
                        {"device_time_share", deviceSeconds > 0.0 ? cameraSeconds / deviceSeconds : 0.0},
                        // fixed mode learns no pixel's variance: its share is not known
                        {"error_share", cameraSampler.mode() == CameraPassMode::Balanced
                                            ? nlohmann::json(cameraSampler.errorShare()) : nlohmann::json(nullptr)}};
        return r;
    }
};

double RenderResult::roiMean(std::size_t k) const
{
    const auto& v = roiBatchMeans.at(k);
    double s = 0.0, W = 0.0;
    for (std::size_t b = 0; b < v.size(); ++b) {
        s += batchWeights[b] * v[b];
        W += batchWeights[b];
    }
    return (v.empty() ? 0.0 : s / W) + (k < roiCamera.size() ? roiCamera[k].first : 0.0);
}

double RenderResult::maxBounceFluxShare() const
{
    const double emitted = static_cast<double>(paths) * emittedFluxPerPath;
    return emitted > 0.0 ? counts.cutFlux / emitted : 0.0;
}

double RenderResult::roiMeanStdErr(std::size_t k) const
{
    const auto& v = roiBatchMeans.at(k);
    if (v.size() < 2)
        return 0.0;
    double m = 0.0, ss = 0.0, W = 0.0;
    for (std::size_t b = 0; b < v.size(); ++b) {
        m += batchWeights[b] * v[b];
        W += batchWeights[b];
    }
    m /= W;
    for (std::size_t b = 0; b < v.size(); ++b)
        ss += batchWeights[b] * (v[b] - m) * (v[b] - m);
    // the light-traced part's batch spread, and the camera part's own variance (independent)
    return std::sqrt(ss / static_cast<double>(v.size() - 1) / W + (k < roiCamera.size() ? roiCamera[k].second : 0.0));
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
    if (settings.rouletteDepth && (*settings.rouletteDepth < 0 || *settings.rouletteDepth > 64))
        throw Error(cat("--roulette-depth ", *settings.rouletteDepth, ": must be in 0..64"));
    if (settings.splitMax < 1 || settings.splitMax > FEN_MAX_BRANCHES)
        throw Error(cat("--split ", settings.splitMax, " must be in 1..", FEN_MAX_BRANCHES, " branches (1: never split)"));
    if (!(settings.splitWeight > 0.0 && settings.splitWeight <= 1e6))
        throw Error(cat("--split-weight ", settings.splitWeight, " must be in (0, 10^6]"));
    if (settings.batches > 1024)
        throw Error(cat("--batches ", settings.batches, " is beyond 1024: every batch has a fixed cost "
                        "(the camera pass, the statistics), and 16 already estimate the noise well"));
    if (settings.paths > 0 && settings.paths < static_cast<std::uint64_t>(settings.batches))
        throw Error(cat("--paths ", settings.paths, " is fewer than the ", settings.batches,
                        " batches: give at least that many paths, or fewer --batches"));
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
