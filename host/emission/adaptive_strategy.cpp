// adaptive_strategy.cpp — the `adaptive` strategy's tables, passes, buffers and descriptor
// (adaptive_strategy.h).
#include "emission/adaptive_strategy.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>

#include "bvh_build.h"
#include "cl/launch.h"
#include "emission/adaptive_grid.h"
#include "emission/adaptive_options.h"
#include "emission/emission_sphere.h"
#include "emission/openings_race.h"
#include "emission/light_levels.h"
#include "emission/portal_planes.h"
#include "trace/device_bvh.h"
#include "io/state_io.h"
#include "util/error.h"
#include "util/integer_cdf.h"
#include "util/fixed_point.h"

namespace fen {

namespace {

// Statistics hold round(Y^2 * 2^32 / ref^2), 128-bit: contributions down to ~1e-5 of the
// reference luminance still register, and 2^95 ref^2 fits before overflowing (lib/accumulate.h).
constexpr int kStatsFixedPointBits = 32;
// The relative target's image estimate is averaged over tiles of this many pixels a side (a
// single pixel's early estimate is mostly noise), and a tile darker than kRelativeFloor of the
// image's mean counts as that bright: a dark tile then weighs at most 1 / kRelativeFloor^2 as much
// as an average one, and one no light has reached yet does not take over the grid.
constexpr int kRelativeTile = 16;
constexpr double kRelativeFloor = 0.02;
// In the base density a portal plane is weighted by |v.n| plus this, so that no plane is written off
// for directions it faces edge-on before anything is measured: cells are wide at first.
constexpr double kPlaneFloor = 0.05;

// The direction (towards the sky) at (s, t): cos(theta) = 1 - s, phi = 2 pi t.
glm::dvec3 skyAt(double s, double t, double* theta, double* phi)
{
    *theta = std::acos(std::clamp(1.0 - s, -1.0, 1.0));
    *phi = 2.0 * M_PI * t;
    return skyDirection(*theta, *phi);
}

class AdaptiveStrategyImpl final : public AdaptiveStrategy {
public:
    AdaptiveStrategyImpl(const EmissionSettings& settings, const EmissionInputs& in)
        : ctx_(in.ctx), opt_(settings.adaptive), portalBase_(opt_.base == EmissionMethod::Portal),
          sky_(in.deviceSky), goniogram_(in.goniogram)
    {
        const auto t0 = std::chrono::steady_clock::now();
        validateAdaptiveOptions(opt_);
        const Scene& scene = in.scene;
        emissionSphere(scene, &centre_, &radius_m_);
        const double ref = referenceLuminance(scene, in.sky);
        statsScale_ = std::ldexp(1.0, kStatsFixedPointBits) / (ref * ref);
        fixedScale_ = in.pixelFixedScale;
        hasSky_ = goniogram_ && goniogram_->integral() > 0.0;
        // With the ground's glow the sky's directions are two unit squares of (s, t): s in [0, 1)
        // above the horizon, [1, 2) below it, so no box straddles the horizon's step.
        const std::uint32_t skyRoots = goniogram_ && goniogram_->hasGround() ? 2u : 1u;
        if (portalBase_)
            planes_ = makePortalPlanes(scene, settings.portals, in.bvhWidth);
        sunY_ = sunIlluminanceY_lux(scene);
        sunDir_ = -scene.sun.travelDirection;

        // Regions: the disk, then the portal planes (their frames' areas).
        regionArea_.push_back(M_PI * radius_m_ * radius_m_);
        for (const auto& f : planes_.frames)
            regionArea_.push_back(f.origin.w);

        // The base density per (direction box, region), over the initial boxes: the disk's share
        // by flux (as `uniform`), the planes' by flux through them.
        std::vector<GridCell> cells;
        const std::uint32_t side = 1u << opt_.initialDepth, skySide = 1u << opt_.initialSkyDepth;
        std::vector<GridCell> dirBoxes;
        if (sunY_ > 0.0 && scene.sun.present) {
            GridCell c;
            c.sun = true;
            dirBoxes.push_back(c);
        }
        if (hasSky_)
            for (std::uint32_t it = 0; it < skySide; ++it)
                for (std::uint32_t is = 0; is < skySide * skyRoots; ++is) {
                    GridCell c;
                    c.skyDepth = static_cast<std::uint32_t>(opt_.initialSkyDepth);
                    c.is = is;
                    c.it = it;
                    dirBoxes.push_back(c);
                }
        const double diskShare = portalBase_ ? opt_.diskShare : 1.0;
        std::vector<double> regionTotal(1 + planes_.frames.size(), 0.0);
        std::vector<std::vector<double>> flux(dirBoxes.size());
        for (std::size_t d = 0; d < dirBoxes.size(); ++d)
            for (std::uint32_t r = 0; r < regionTotal.size(); ++r) {
                GridCell c = dirBoxes[d];
                c.region = r;
                flux[d].push_back(boxFlux(c, 64));
                regionTotal[r == 0 ? 0 : 1] += flux[d].back();
            }
        // The grid's first cells, counted before any is made: a combination of depths (and many
        // portal planes) can ask for more than any machine holds; that is the cell limit's error.
        std::uint64_t lit = 0;
        for (std::size_t d = 0; d < dirBoxes.size(); ++d)
            for (std::uint32_t r = 0; r < regionTotal.size(); ++r)
                lit += flux[d][r] > 0.0 && regionTotal[r == 0 ? 0 : 1] > 0.0;
        const std::uint64_t initialCells = lit * std::uint64_t{side} * side;
        if (initialCells > opt_.maxCells)
            throw Error(cat("--adaptive-max-cells ", opt_.maxCells, " is below the ", initialCells,
                            " cells the grid starts with (", lit, " lit direction boxes and regions x 4^",
                            opt_.initialDepth, " origin boxes): lower --adaptive-initial-depth or "
                            "--adaptive-initial-sky-depth, or raise --adaptive-max-cells"));
        cells.reserve(static_cast<std::size_t>(initialCells));
        for (std::size_t d = 0; d < dirBoxes.size(); ++d)
            for (std::uint32_t r = 0; r < regionTotal.size(); ++r) {
                const double share = r == 0 ? diskShare : 1.0 - diskShare;
                const double total = regionTotal[r == 0 ? 0 : 1];
                if (!(flux[d][r] > 0.0) || !(total > 0.0))
                    continue;
                for (std::uint32_t iy = 0; iy < side; ++iy)
                    for (std::uint32_t ix = 0; ix < side; ++ix) {
                        GridCell c = dirBoxes[d];
                        c.region = r;
                        c.depth = static_cast<std::uint32_t>(opt_.initialDepth);
                        c.ix = ix;
                        c.iy = iy;
                        c.base = share * flux[d][r] / total / (side * side);
                        cells.push_back(c);
                    }
            }
        if (cells.empty()) {
            // No light at all: one (zero-weight) sun cell keeps the tables valid; paths carry 0.
            GridCell c;
            c.sun = true;
            c.base = 1.0;
            cells.push_back(c);
        }
        if (cells.size() > opt_.maxCells)
            throw Error(cat("--adaptive-max-cells ", opt_.maxCells, " is below the ", cells.size(),
                            " cells the grid starts with"));
        GridLearning learning;
        learning.estimate = opt_.estimate;
        learning.defensive = opt_.defensive;
        learning.splitGain = opt_.splitGain;
        learning.maxDepth = static_cast<std::uint32_t>(opt_.maxDepth);
        learning.maxSkyDepth = static_cast<std::uint32_t>(opt_.maxSkyDepth);
        learning.maxCells = opt_.maxCells;
        learning.priorPaths = opt_.priorPaths;
        learning.skyRoots = skyRoots;
        grid_ = std::make_unique<AdaptiveGrid>(std::move(cells), learning, [this](const GridCell& c, double share[4]) {
            double total = 0.0;
            for (std::uint32_t q = 0; q < 4; ++q) {
                GridCell k = c;
                k.skyDepth = c.skyDepth + 1;
                k.is = 2 * c.is + (q & 1u);
                k.it = 2 * c.it + (q >> 1);
                share[q] = boxFlux(k, 16);
                total += share[q];
            }
            for (std::uint32_t q = 0; q < 4; ++q)
                share[q] = total > 0.0 ? share[q] / total : 0.25;
        });

        createBuffers(scene);
        // the aim learns its share from sums the guide keeps per slot, beside the weight windows'
        // (the options refuse --adaptive-aim-share learned without windows)
        GuideOptions guideOptions = opt_.guide;
        OpeningAimOptions aimOptions = opt_.aim;
        aimOptions.learnShare = aimOptions.enabled && aimOptions.learnShare && guideOptions.enabled && guideOptions.window;
        guideOptions.aimSums = aimOptions.learnShare;
        guide_ = std::make_unique<FirstBounceGuide>(ctx_, guideOptions, centre_, radius_m_);
        deviceBytes_ += guide_->deviceBytes();
        aim_ = std::make_unique<OpeningAim>(ctx_, aimOptions, &scene);
        deviceBytes_ += aim_->deviceBytes();
        if (opt_.relativeTarget) {
            filmWidth_ = in.filmWidth;
            filmHeight_ = in.filmHeight;
            const std::size_t px = static_cast<std::size_t>(filmWidth_) * filmHeight_;
            pixelScaleHost_.assign(std::max<std::size_t>(px, 1), 1.0f);  // before any estimate: absolute
            pixelScale_ = ctx_.buffer(CL_MEM_READ_ONLY, pixelScaleHost_.size() * 4, "adaptive pixel scale",
                                      pixelScaleHost_.data());
            deviceBytes_ += pixelScaleHost_.size() * 4;
        }
        upload();
        passSize_ = opt_.firstPass;
        learnSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }

    EmissionMethod method() const override { return EmissionMethod::Adaptive; }
    EmissionKernels kernels() const override
    {
        EmissionKernels k;
        k.emitProgram = "emit_adaptive.cl";
        k.gatherStats = true;
        k.cellStats = &stats_;
        k.statsScale = statsScale_;
        k.statsPixelScale = opt_.relativeTarget ? &pixelScale_ : nullptr;
        k.guide = guide_.get();  // off: slots 0, placeholders
        k.aim = aim_.get();      // off or no glass: nothing aimed at
        k.openingWalks = opt_.openingsShare > 0.0 || opt_.openingsAuto;
        return k;
    }
    std::vector<SummedBuffer> summedBuffers() const override
    {
        static_assert(FEN_CELL_SUM_LO == 0 && FEN_CELL_SUMSQ_LO == 2 && FEN_CELL_CONNECTIONS == 4 &&
                          FEN_CELL_STATS_WORDS == 5, "a cell's statistics: two 128-bit sums and a count");
        return {{&stats_, statsParts(), {2, 2, 1}}, guide_->summed(), guide_->windowSummed(),
                aim_->summed()};
    }
    void bindEmitArgs(cl::Kernel& emit, cl_uint first) override
    {
        ocl::setKernelArgsFrom(emit, first, params_, cellAlias_, cellBuf_, sky_.theta, sky_.phi, sky_.values,
                               frames_, portalBvh_->nodes(), portalBvh_->packets());
    }
    // The flux through the disk, whatever the base: the cells cover every line once
    // (tests/kernels/adaptive_sampling_test.cpp).
    double emittedFluxPerPath() const override
    {
        return M_PI * radius_m_ * radius_m_ * (sunY_ + (goniogram_ ? goniogram_->integral() : 0.0));
    }
    double batchWeight(double pathsShare) override
    {
        // the predicted precision N^2 / sum n_p V_p grows with the batch's paths N by itself
        const double w = opt_.weighBatches ? lastBatchWeight_ : pathsShare;
        batchWeights_.push_back(w);
        return w;
    }

    // The relative target: a contribution to pixel p counts as Y * mean / max(tile(p), floor mean),
    // i.e. relative to its pixel's brightness in units of the image's mean.
    void imageEstimate(const std::vector<double>& luminance) override
    {
        if (!opt_.relativeTarget || luminance.size() != pixelScaleHost_.size())
            return;
        const int w = filmWidth_, h = filmHeight_, t = kRelativeTile;
        const int tw = (w + t - 1) / t, th = (h + t - 1) / t;
        std::vector<double> tileSum(static_cast<std::size_t>(tw) * th, 0.0), tileCount(tileSum.size(), 0.0);
        double total = 0.0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const double v = luminance[static_cast<std::size_t>(y) * w + x];
                const double Y = std::isfinite(v) && v > 0.0 ? v : 0.0;
                const std::size_t k = static_cast<std::size_t>(y / t) * tw + x / t;
                tileSum[k] += Y;
                tileCount[k] += 1.0;
                total += Y;
            }
        const double mean = total / (static_cast<double>(w) * h);
        if (!(mean > 0.0))
            return;  // nothing seen yet: keep the factors
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const std::size_t k = static_cast<std::size_t>(y / t) * tw + x / t;
                const double tile = tileSum[k] / tileCount[k];
                pixelScaleHost_[static_cast<std::size_t>(y) * w + x] =
                    static_cast<float>(mean / std::max(tile, kRelativeFloor * mean));
            }
        ctx_.queue().enqueueWriteBuffer(pixelScale_, CL_TRUE, 0, pixelScaleHost_.size() * 4, pixelScaleHost_.data());
    }
    std::uint64_t passLimit(std::uint64_t batchLeft) const override
    {
        // a raced pass stops at its half (host/emission/openings_race.h), then goes on at the trial's
        // share: half of what the pass will run, its size or the batch's rest, whichever ends first
        if (race_.racing() && !race_.halfDone()) {
            if (passPaths_ == 0)
                raceHalf_ = race_.half(std::min(passSize_, batchLeft));
            if (passPaths_ < raceHalf_)
                return raceHalf_ - passPaths_;
        }
        return passSize_ - passPaths_;
    }

    double openingsShare() const override { return race_.share(); }
    bool learningPending() const override { return race_.pending(); }

    void afterPaths(std::uint64_t paths, std::uint64_t rays, bool batchEnd) override
    {
        if (paths == 0)
            return;
        passPaths_ += paths;
        passRays_ += rays;
        if (passPaths_ < passSize_ && !batchEnd) {
            if (race_.racing() && !race_.halfDone() && raceHalf_ > 0 && passPaths_ >= raceHalf_) {
                firstHalf_ = readStats();
                firstHalfPaths_ = passPaths_;
                race_.afterHalf(passMoments(firstHalf_));
            }
            return;
        }
        const auto t0 = std::chrono::steady_clock::now();
        const RacePass race = learn();
        if (batchEnd) {
            double paths = 0.0, varianceTimesPaths = 0.0;
            for (const auto& [n, v] : batchPasses_) {
                paths += n;
                varianceTimesPaths += n * v;
            }
            // The batch's image is the path-weighted mean of its passes': variance per path
            // sum n_p V_p / N, so its precision is N^2 / sum n_p V_p.
            lastBatchWeight_ = varianceTimesPaths > 0.0 ? paths * paths / varianceTimesPaths : 1.0;
            batchPasses_.clear();
        }
        ++passes_;
        passPaths_ = 0;
        passRays_ = 0;
        passSize_ = std::min<std::uint64_t>(passSize_ * 2, std::uint64_t{1} << 62);
        if (std::getenv("FEN_ADAPTIVE_LOG"))
            std::fprintf(stderr, "  race: %.0f paths, %.4f rays/path, second moment/path light %.4g walks %.4g, share %.3g\n",
                         race.paths, race.rays / race.paths, race.lightSumSq / race.paths, race.walkSumSq / race.paths,
                         race_.share());
        race_.afterPass(race, aim_->aimedTriangles() > 0, passSize_);
        learnSeconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }

    void saveState(StateWriter& w) const override
    {
        grid_->save(w);
        w.u64("adaptive.pass_size", passSize_);
        w.u64("adaptive.passes", static_cast<std::uint64_t>(passes_));
        w.f64s("adaptive.weights", {lastBatchWeight_, learnSeconds_});
        w.f64s("adaptive.batch_weights", batchWeights_);
        if (opt_.guide.enabled)
            guide_->save(w);
        if (opt_.aim.enabled)
            aim_->save(w);
        if (opt_.openingsAuto)  // absent otherwise: a checkpoint without the race still resumes
            race_.save(w);
    }
    void loadState(StateReader& r) override
    {
        // Between batches: no pass is half done, and the statistics on the device are cleared.
        grid_->load(r, static_cast<std::uint32_t>(regionArea_.size()));
        passSize_ = r.u64("adaptive.pass_size", std::uint64_t{1} << 62);
        if (passSize_ == 0)
            r.fail("adaptive.pass_size", "zero");
        passes_ = static_cast<int>(r.u64("adaptive.passes", 1u << 30));
        const std::vector<double> w = r.f64s("adaptive.weights", 2, true);
        lastBatchWeight_ = w[0];
        learnSeconds_ = w[1];
        batchWeights_ = r.f64s("adaptive.batch_weights", 1u << 20);
        passPaths_ = passRays_ = 0;
        batchPasses_.clear();
        ctx_.queue().enqueueFillBuffer(stats_, cl_ulong(0), 0, statsParts() * FEN_CELL_STATS_WORDS * 8);
        if (opt_.guide.enabled)
            guide_->load(r);
        if (opt_.aim.enabled)
            aim_->load(r);
        if (opt_.openingsAuto)
            race_.load(r);
        upload();
    }

    const AdaptiveGrid& grid() const override { return *grid_; }
    const std::vector<double>& realisedProbabilities() const override { return realised_; }
    void setProbabilities(const std::vector<double>& p) override
    {
        grid_->setProbabilities(p);
        upload();
    }

    nlohmann::json report() const override
    {
        const auto& cells = grid_->cells();
        // Developers' view of the learned grid (README: Diagnostics).
        if (const char* dump = std::getenv("FEN_ADAPTIVE_DUMP"); dump && *dump) {
            FILE* f = std::fopen(dump, "w");
            if (!f)
                throw Error(cat("FEN_ADAPTIVE_DUMP=", dump, ": cannot write"));
            std::fprintf(f, "sun,region,depth,ix,iy,skydepth,is,it,base,prob,learned,paths,sum,sumsq,connections\n");
            for (std::size_t i = 0; i < cells.size(); ++i) {
                const GridCell& c = cells[i];
                const GridCell::Stats t = c.total();
                std::fprintf(f, "%d,%u,%u,%u,%u,%u,%u,%u,%g,%g,%g,%g,%g,%g,%g\n", c.sun ? 1 : 0, c.region, c.depth,
                             c.ix, c.iy, c.skyDepth, c.is, c.it, c.base, c.prob, grid_->learned()[i], t.paths, t.sum,
                             t.sumSq, t.connections);
            }
            std::fclose(f);
        }
        double sun = 0.0, disk = 0.0;
        for (const GridCell& c : cells) {
            sun += c.sun ? c.prob : 0.0;
            disk += c.region == FEN_REGION_DISK ? c.prob : 0.0;
        }
        nlohmann::json j = {
            {"base", methodName(opt_.base)},
            {"initial_sky_depth", opt_.initialSkyDepth},
            {"max_sky_depth", opt_.maxSkyDepth},
            {"deepest_sky", grid_->deepestSky()},
            {"cells", cells.size()},
            {"max_cells", opt_.maxCells},
            {"initial_depth", opt_.initialDepth},
            {"max_depth", opt_.maxDepth},
            {"deepest", grid_->deepest()},
            {"memory_bytes", deviceBytes_},
            {"passes", passes_},
            {"checksum", grid_->checksum()},
            {"batch_weights", relativeWeights()},
            {"first_pass_paths", opt_.firstPass},
            {"target", opt_.relativeTarget ? "relative" : "absolute"},
            {"defensive", opt_.defensive},
            {"estimate", estimateName(opt_.estimate)},
            {"split_gain", opt_.splitGain},
            {"prior_paths", opt_.priorPaths},
            {"learn_seconds", learnSeconds_},
            {"paths_learned_from", grid_->paths()},
            {"connections_per_path", grid_->paths() > 0.0 ? grid_->connections() / grid_->paths() : 0.0},
            {"probability", {{"sun", sun}, {"disk", disk}, {"portals", 1.0 - disk}}},
            {"sun_illuminance_lux", sunY_},
            {"sky_integral_cd_m2_sr", goniogram_ ? goniogram_->integral() : 0.0},
            {"disk_radius_m", radius_m_},
            {"guide", guide_->report()},
            {"aim", aim_->report()},
            // the share of paths started on the aimed panes (DESIGN.md §3.6; counters.opening_walks):
            // the last pass's, and how it was chosen (host/emission/openings_race.h)
            {"openings_share", race_.share()},
            {"openings_share_auto", opt_.openingsAuto},
            {"openings_race", race_.report()}};
        if (portalBase_) {
            j["disk_share"] = opt_.diskShare;
            j["portal_nodes"] = planes_.set.nodes;
            j["portal_planes"] = planes_.frames.size();
        }
        return j;
    }

private:
    // The base density's weight of the rays of a cell's direction box through its region
    // (midpoint rule, n x n points: it only shapes the base and the priors; the paths' weights use
    // the exact density): the flux for the disk, per unit area of it; for a portal plane the flux
    // through it, with kPlaneFloor.
    double boxFlux(const GridCell& c, int n) const
    {
        const auto regionWeight = [&](const glm::dvec3& towardsSky) {
            if (c.region == FEN_REGION_DISK)
                return 1.0;
            const glm::dvec3& nrm = planes_.normal[c.region - 1];
            return planes_.area_m2[c.region - 1] * (std::fabs(glm::dot(towardsSky, nrm)) + kPlaneFloor);
        };
        if (c.sun)
            return sunY_ * regionWeight(sunDir_);
        if (!hasSky_)
            return 0.0;
        const double size = std::ldexp(1.0, -static_cast<int>(c.skyDepth));
        double sum = 0.0;
        for (int a = 0; a < n; ++a)
            for (int b = 0; b < n; ++b) {
                double theta, phi;
                const glm::dvec3 w = skyAt((c.is + (a + 0.5) / n) * size, (c.it + (b + 0.5) / n) * size, &theta, &phi);
                sum += goniogram_->eval(theta, phi) * regionWeight(w);
            }
        return sum / (n * n) * 2.0 * M_PI * size * size;
    }

    // The counted batches' weights over their mean.
    std::vector<double> relativeWeights() const
    {
        double mean = 0.0;
        for (double w : batchWeights_)
            mean += w / static_cast<double>(batchWeights_.size());
        std::vector<double> r;
        for (double w : batchWeights_)
            r.push_back(mean > 0.0 ? w / mean : 1.0);
        return r;
    }

    void createBuffers(const Scene& scene)
    {
        ocl::Context& c = ctx_;
        const std::size_t maxCells = opt_.maxCells;
        std::size_t columns = 2;
        while (columns < maxCells)
            columns *= 2;
        const auto add = [this](std::size_t bytes) { deviceBytes_ += std::max<std::size_t>(bytes, 4); };
        cellBuf_ = c.buffer(CL_MEM_READ_ONLY, maxCells * sizeof(dev::AdaptiveCell), "adaptive cells");
        add(maxCells * sizeof(dev::AdaptiveCell));
        cellAlias_ = c.buffer(CL_MEM_READ_ONLY, columns * 8, "adaptive cell table");
        add(columns * 8);
        // the cells' parts, then the openings' walks' (shared/fen_emission.h FEN_WALK_PARTS)
        const std::size_t statsBytes = (maxCells * FEN_CELL_PARTS + FEN_WALK_PARTS) * FEN_CELL_STATS_WORDS * 8;
        stats_ = c.buffer(CL_MEM_READ_WRITE, statsBytes, "adaptive cell statistics");
        add(statsBytes);
        c.queue().enqueueFillBuffer(stats_, cl_ulong(0), 0, statsBytes);
        const auto upload = [&](const auto& v, const char* what) {
            add(v.size() * sizeof(v[0]));
            return c.buffer(CL_MEM_READ_ONLY, v.size() * sizeof(v[0]), what, v.empty() ? nullptr : v.data());
        };
        frames_ = upload(planes_.frames, "portal frames");
        if (!portalBase_) {
            // Placeholders: a one-triangle tree far away, never traversed over a uniform base.
            const float far = 1e30f;
            const std::vector<Triangle> none = {{{far, far, far}, {far, far, far + 1}, {far, far + 1, far}}};
            planes_.bvh = flattenBvh(buildBinnedSah(none), none, 2);
        }
        portalBvh_ = std::make_unique<DeviceBvh>(c, planes_.bvh);
        add(planes_.bvh.nodeBytes() + planes_.bvh.packetBytes());
        dev::AdaptiveParams p{};
        const glm::dvec3 E = scene.sun.present ? scene.sun.illuminanceRgb_lux : glm::dvec3(0.0);
        const glm::dvec3 sw = E * sunConeFactor(scene.sun);
        p.sun_weight = {float(sw.r), float(sw.g), float(sw.b), 0.0f};
        p.portal_base = portalBase_ ? 1u : 0u;
        params_ = c.buffer(CL_MEM_READ_ONLY, sizeof p, "adaptive parameters", &p);
        deviceParams_ = p;
    }

    // The grid's probabilities as the device draws them (integer alias table: the weights use the
    // probabilities realised), with each cell's weight.
    void upload()
    {
        const auto& cells = grid_->cells();
        std::vector<double> prob(cells.size());
        for (std::size_t i = 0; i < cells.size(); ++i)
            prob[i] = cells[i].prob;
        const IntegerCdf table = makeIntegerCdf(prob);
        realised_.resize(cells.size());
        hostCells_.resize(cells.size());
        for (std::size_t i = 0; i < cells.size(); ++i) {
            const GridCell& c = cells[i];
            realised_[i] = table.probability(i);
            const double size = std::ldexp(1.0, -static_cast<int>(c.depth));
            const double skySize = std::ldexp(1.0, -static_cast<int>(c.skyDepth));
            dev::AdaptiveCell d{};
            d.box = {float(c.ix * size), float(c.iy * size), float(size), float(size)};
            d.dirs = c.sun ? dev::fen_float4{0.0f, 0.0f, 0.0f, 0.0f}
                           : dev::fen_float4{float(c.is * skySize), float(c.it * skySize), float(skySize), float(skySize)};
            d.region = c.region;
            const double solidAngle = c.sun ? 1.0 : 2.0 * M_PI * c.skyArea();
            d.weight = static_cast<float>(regionArea_[c.region] * c.boxArea() * solidAngle / realised_[i]);
            hostCells_[i] = d;
        }
        hostAlias_ = table.alias;
        // The next pass's variance relative to the base density's, both as the statistics so far
        // predict: fixed before the pass runs, so weighting the batches by it keeps them unbiased.
        std::vector<double> base(cells.size());
        for (std::size_t i = 0; i < cells.size(); ++i)
            base[i] = cells[i].base;
        const double baseVariance = grid_->predictedVariance(base);
        nextVariance_ = baseVariance > 0.0 ? grid_->predictedVariance(realised_) / baseVariance : 1.0;
        deviceParams_.cell_alias_shift = table.aliasShift;
        deviceParams_.cells = static_cast<std::uint32_t>(cells.size());
        deviceParams_.walk_part = static_cast<std::uint32_t>(FEN_CELL_PARTS * cells.size());
        auto& q = ctx_.queue();
        q.enqueueWriteBuffer(cellBuf_, CL_FALSE, 0, hostCells_.size() * sizeof(dev::AdaptiveCell), hostCells_.data());
        q.enqueueWriteBuffer(cellAlias_, CL_FALSE, 0, hostAlias_.size() * 4, hostAlias_.data());
        q.enqueueWriteBuffer(params_, CL_TRUE, 0, sizeof deviceParams_, &deviceParams_);
    }

    // The statistics parts in use: the cells', then the walks'.
    std::size_t statsParts() const { return FEN_CELL_PARTS * grid_->cells().size() + FEN_WALK_PARTS; }
    // Their words as the device holds them now (a blocking read).
    std::vector<std::uint64_t> readStats() const
    {
        std::vector<std::uint64_t> raw(statsParts() * FEN_CELL_STATS_WORDS);
        ctx_.queue().enqueueReadBuffer(stats_, CL_TRUE, 0, raw.size() * 8, raw.data());
        return raw;
    }

    // What the race measures of the pass so far: paths, rays, and the squares of the contributions
    // as the image got them (not over the base), the light paths' and the walks'.
    RacePass passMoments(const std::vector<std::uint64_t>& raw) const
    {
        const std::size_t n = FEN_CELL_PARTS * grid_->cells().size();
        RacePass race{static_cast<double>(passPaths_), static_cast<double>(passRays_), 0.0, 0.0};
        for (std::size_t i = 0; i < statsParts(); ++i)
            (i < n ? race.lightSumSq : race.walkSumSq) +=
                fixed128(raw.data() + FEN_CELL_STATS_WORDS * i + FEN_CELL_SUMSQ_LO) / statsScale_;
        return race;
    }

    // Reads the pass's statistics into the grid, learns, uploads the new grid, clears the counts.
    // Records the pass's variance relative to the base density's, as predicted before it ran, and
    // returns what the race measures of the pass. A raced pass's grid learns from its first half
    // alone: in the second, at the trial's share, the light that crossed a listed pane was the
    // walks' and is missing from the cells, which would teach the grid of a render that may go on
    // without walks that those cells bring less than they do.
    RacePass learn()
    {
        const std::size_t n = FEN_CELL_PARTS * grid_->cells().size();
        const std::vector<std::uint64_t> raw = readStats();
        auto& q = ctx_.queue();
        const bool raced = !firstHalf_.empty() && passPaths_ > firstHalfPaths_;
        const std::vector<std::uint64_t>& learned = raced ? firstHalf_ : raw;
        const double learnedPaths = static_cast<double>(raced ? firstHalfPaths_ : passPaths_);
        std::vector<GridCell::Stats> parts(n);
        const auto& cells = grid_->cells();
        for (std::size_t i = 0; i < n; ++i) {
            const std::uint64_t* w = learned.data() + FEN_CELL_STATS_WORDS * i;
            // Lambda = Y P(cell) / P_base(cell): the contribution had the base density emitted it.
            const std::size_t cell = i / FEN_CELL_PARTS;
            const double toBase = realised_[cell] / cells[cell].base;
            parts[i].sum = fixed128(w + FEN_CELL_SUM_LO) / fixedScale_ * toBase;
            parts[i].sumSq = fixed128(w + FEN_CELL_SUMSQ_LO) / statsScale_ * toBase * toBase;
            // Paths are not counted on the device: the expectation, exact in the mean
            // (shared/fen_emission.h).
            parts[i].paths = learnedPaths * realised_[cell] / FEN_CELL_PARTS;
            parts[i].connections = static_cast<double>(w[FEN_CELL_CONNECTIONS]);
        }
        grid_->addPass(parts);
        const RacePass race = passMoments(raw);
        firstHalf_.clear();
        const double variance = nextVariance_;
        batchPasses_.push_back({static_cast<double>(passPaths_), variance});
        double passConn = 0.0;
        for (const auto& p : parts)
            passConn += p.connections;
        const std::size_t splits = grid_->update();
        if (std::getenv("FEN_ADAPTIVE_LOG"))
            std::fprintf(stderr, "pass %d: %llu paths, %.4f contributions/path, variance %.3g, %zu splits -> %zu cells\n",
                         passes_, static_cast<unsigned long long>(passPaths_), passConn / passPaths_, variance, splits,
                         grid_->cells().size());
        q.enqueueFillBuffer(stats_, cl_ulong(0), 0, statsParts() * FEN_CELL_STATS_WORDS * 8);
        upload();
        guide_->learn();
        const FirstBounceGuide::AimSums sums = guide_->passAimSums();
        aim_->learnShare(sums.mixed, sums.aimed);
        aim_->learn();
        return race;
    }

    ocl::Context& ctx_;
    AdaptiveOptions opt_;
    bool portalBase_;
    glm::dvec3 centre_{0.0};
    double radius_m_ = 0.0, statsScale_ = 0.0, fixedScale_ = 0.0;
    const DeviceSky& sky_;
    const std::optional<Goniogram>& goniogram_;
    bool hasSky_ = false;
    double sunY_ = 0.0;
    glm::dvec3 sunDir_{0.0};  // towards the sun
    PortalPlanes planes_;
    std::vector<double> regionArea_, realised_;
    std::unique_ptr<AdaptiveGrid> grid_;
    std::unique_ptr<FirstBounceGuide> guide_;
    std::unique_ptr<OpeningAim> aim_;
    std::vector<dev::AdaptiveCell> hostCells_;
    std::vector<std::uint32_t> hostAlias_;
    dev::AdaptiveParams deviceParams_{};
    cl::Buffer params_, cellAlias_, cellBuf_, stats_, frames_;
    std::unique_ptr<DeviceBvh> portalBvh_;
    cl::Buffer pixelScale_;              // the relative target's factor per pixel
    std::vector<float> pixelScaleHost_;
    int filmWidth_ = 0, filmHeight_ = 0;
    std::size_t deviceBytes_ = 0;
    std::uint64_t passSize_ = 0, passPaths_ = 0, passRays_ = 0;
    OpeningsRace race_{opt_.openingsAuto, opt_.openingsShare, opt_.openingsRacePaths};  // the walks' share, pass by pass
    mutable std::uint64_t raceHalf_ = 0;  // the raced pass's first half: set when it starts (passLimit)
    std::vector<std::uint64_t> firstHalf_;  // ... its statistics when it ended (what the grid learns)
    std::uint64_t firstHalfPaths_ = 0;
    int passes_ = 0;
    double learnSeconds_ = 0.0;
    double nextVariance_ = 1.0;       // variance per path of the pass about to run over the base's, predicted
    std::vector<std::pair<double, double>> batchPasses_;  // this batch's passes: paths, variance
    double lastBatchWeight_ = 1.0;
    std::vector<double> batchWeights_;
};

}  // namespace

std::unique_ptr<AdaptiveStrategy> makeAdaptiveStrategy(const EmissionSettings& settings,
                                                       const EmissionInputs& in)
{
    return std::make_unique<AdaptiveStrategyImpl>(settings, in);
}

// Roulette from the 3rd interaction: its paths are aimed in from the start
// (docs/results/termination.md).
const StrategyDescriptor kAdaptiveStrategy = {
    EmissionMethod::Adaptive,
    "adaptive",
    3,
    makeAdaptiveOptionBlock,
    [](const EmissionSettings& e) { return e.adaptive.base == EmissionMethod::Portal; },
    adaptiveFingerprint,
    [](const EmissionSettings& e, const EmissionInputs& in) -> std::unique_ptr<EmissionStrategy> {
        return makeAdaptiveStrategy(e, in);
    },
};

}  // namespace fen
