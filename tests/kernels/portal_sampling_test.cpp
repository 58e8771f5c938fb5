// portal_sampling_test.cpp — portal emission against the paper's equations: the triangle choice
// against eq. (1) and the sky-cell choice against eq. (2) by chi-square (p > 1e-3, fixed seeds),
// the cell weights against an independent quadrature, and the emitted weights against the flux
// through the portal (4 sigma of the sample's standard error).
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "cl/launch.h"
#include "emission/light_levels.h"
#include "emission/portal_emission.h"
#include "emission/uniform_emission.h"
#include "io/image.h"
#include "render/device_scene.h"
#include "sky/sky_spec.h"
#include "support/cl_fixture.h"
#include "support/emit_probe.h"
#include "support/render_support.h"
#include "support/statistics.h"
#include "support/test_scenes.h"
#include "trace/device_bvh.h"

namespace fen {
namespace {

using test::rect;

constexpr double kMinP = 1e-3;

// Portals of several orientations and sizes: a south window (2 triangles), an east window, a
// skylight, a tilted roof window.
Scene portalScene(double sunAltitude = 35.0)
{
    test::SceneBuilder b;
    const int m = b.material("m", glm::vec3(0.5f));
    b.add("floor", rect({0, 0, 0}, {4, 0, 0}, {0, 0, 4}), m);
    b.add("south", rect({1, 1, 4}, {1.5f, 0, 0}, {0, 1, 0}), m, PortalMark::Panes);
    b.add("east", rect({4, 1, 1}, {0, 0, 0.8f}, {0, 1.2f, 0}), m, PortalMark::Panes);
    b.add("skylight", rect({2, 3, 2}, {0.5f, 0, 0}, {0, 0, 0.5f}), m, PortalMark::Panes);
    b.add("tilted", rect({0.2f, 2.5f, 1}, {0.6f, 0, 0}, {0, 0.5f, 0.7f}), m, PortalMark::Panes);
    b.sun(sunAltitude, 150.0, 50000.0);
    b.cieSky(12, 3000.0, sunAltitude, 150.0);
    b.camera({1, 1.5, 1}, {2, 0, 2}, {0, 1, 0}, 60.0);
    return b.build();
}

// A scene's sky and its portal emission tables (bins of the BVH8 layout).
struct PortalTables {
    std::optional<Goniogram> sky;
    SkyTables tables;
    PortalEmission pe;
};

PortalTables portalTables(const Scene& scene)
{
    PortalTables t;
    t.sky = buildSky(scene.sky);
    t.tables = makeSkyTables(t.sky);
    t.pe = setupPortalEmission(scene, t.tables, t.sky, "", 8);
    return t;
}

// Triangle t's share of eq. (1) over a set of directions: sum over them of weight * S_t |v . n_t|,
// from each triangle's own geometry (not the implementation's groups).
std::vector<double> triangleWeights(const PortalSet& P, const std::vector<std::pair<glm::dvec3, double>>& dirs)
{
    std::vector<double> w(P.triangles.size(), 0.0);
    for (std::size_t t = 0; t < P.triangles.size(); ++t) {
        const Triangle& tr = P.triangles[t];
        const glm::dvec3 c = glm::cross(glm::dvec3(tr.p1 - tr.p0), glm::dvec3(tr.p2 - tr.p0));
        for (const auto& [v, weight] : dirs)
            w[t] += weight * 0.5 * std::fabs(glm::dot(c, v));
    }
    return w;
}

// The device's triangle choice in direction bin `bin` for direction v, n draws.
std::vector<double> drawTriangles(ocl::Context& ctx, const PortalEmission& pe, std::uint32_t bin,
                                  const glm::dvec3& v, std::uint32_t n)
{
    cl::Kernel k(ctx.program("test_portal_probes.cl", {"FEN_BVH_WIDTH=8"}), "portal_pick_probe");
    auto buf = [&](const auto& x, const char* what) {
        return ctx.buffer(CL_MEM_READ_ONLY, x.size() * sizeof(x[0]), what, x.data());
    };
    const cl::Buffer gb = buf(pe.groups, "groups"), ab = buf(pe.groupAlias, "group alias"),
                     qb = buf(pe.groupRatio, "group ratio"), rb = buf(pe.groupRange, "range"),
                     cb = buf(pe.triangleCdf, "cdf");
    cl::Buffer out = ctx.buffer(CL_MEM_WRITE_ONLY, n * 4, "picks");
    const cl_float4 dir = {{float(v.x), float(v.y), float(v.z), 0.0f}};
    ocl::setKernelArgs(k, gb, ab, qb, rb, cb, static_cast<std::uint32_t>(pe.groups.size()), pe.groupAliasShift,
                       bin, dir, out, n, std::uint32_t{9});
    ocl::launch(ctx, k, "portal_pick_probe", n);
    std::vector<std::uint32_t> pick(n);
    ctx.queue().enqueueReadBuffer(out, CL_TRUE, 0, n * 4, pick.data());
    std::vector<double> obs(pe.portals.triangles.size(), 0.0);
    for (auto t : pick) {
        if (t >= obs.size()) {
            ADD_FAILURE() << "pick " << t << " out of range";
            break;
        }
        obs[t] += 1.0;
    }
    return obs;
}

TEST(PortalSampling, TriangleChoiceFollowsEquation1PerDirectionBin)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const Scene scene = portalScene();
    const PortalTables t = portalTables(scene);
    const auto& P = t.pe.portals;
    const std::uint32_t n = 400000;
    // The sun's bin (a point sun): eq. (1) at its direction exactly.
    {
        const std::vector<double> obs = drawTriangles(*ctx, t.pe, 0, scene.sun.travelDirection, n);
        std::vector<double> exp = triangleWeights(P, {{scene.sun.travelDirection, 1.0}});
        const double sum = std::accumulate(exp.begin(), exp.end(), 0.0);
        for (auto& e : exp)
            e *= n / sum;
        EXPECT_GT(test::chiSquarePValue(obs, exp), kMinP) << "the sun's bin";
    }
    // Two sky bins (high and low): eq. (1) integrated over the bin's cells against the sky's
    // luminance, by a midpoint rule of its own.
    const std::uint32_t R = t.tables.thetaNodes - 1, C = t.tables.phiNodes - 1;
    for (const std::uint32_t cell : {C / 3, (R - 1) * C + 2 * C / 3}) {
        const std::uint32_t bin = t.pe.cellBin.at(cell);
        ASSERT_GE(bin, 1u);
        std::vector<std::pair<glm::dvec3, double>> dirs;
        const int m = 6;
        for (std::uint32_t k = 0; k < t.tables.cells; ++k) {
            if (t.pe.cellBin[k] != bin)
                continue;
            const std::uint32_t i = k / C, j = k % C;
            const double t0 = t.sky->theta()[i], t1 = t.sky->theta()[i + 1], p0 = t.sky->phi()[j], p1 = t.sky->phi()[j + 1];
            for (int a = 0; a < m; ++a)
                for (int b = 0; b < m; ++b) {
                    const double th = t0 + (t1 - t0) * (a + 0.5) / m, ph = p0 + (p1 - p0) * (b + 0.5) / m;
                    dirs.push_back({skyDirection(th, ph), t.sky->eval(th, ph) * std::sin(th) * (t1 - t0) * (p1 - p0)});
                }
        }
        ASSERT_FALSE(dirs.empty());
        // The direction handed over only decides the weight, not the choice.
        const std::vector<double> obs = drawTriangles(*ctx, t.pe, bin, -dirs.front().first, n);
        std::vector<double> exp = triangleWeights(P, dirs);
        const double sum = std::accumulate(exp.begin(), exp.end(), 0.0);
        for (auto& e : exp)
            e *= n / sum;
        EXPECT_GT(test::chiSquarePValue(obs, exp), kMinP) << "sky bin " << bin;
    }
}

// sum_t S_t ∫_cell |v . n_t| g dv, by a midpoint rule fine enough to ignore (independent of the
// implementation's flux-vector shortcut).
double cellWeightByQuadrature(const Goniogram& g, const PortalSet& P, std::size_t i, std::size_t j)
{
    const int m = 24;
    const double t0 = g.theta()[i], t1 = g.theta()[i + 1], p0 = g.phi()[j], p1 = g.phi()[j + 1];
    double s = 0.0;
    for (int a = 0; a < m; ++a)
        for (int b = 0; b < m; ++b) {
            const double th = t0 + (t1 - t0) * (a + 0.5) / m, ph = p0 + (p1 - p0) * (b + 0.5) / m;
            const glm::dvec3 v = skyDirection(th, ph);
            double w = 0.0;
            for (const Triangle& tr : P.triangles)
                w += 0.5 * std::fabs(glm::dot(glm::cross(glm::dvec3(tr.p1 - tr.p0), glm::dvec3(tr.p2 - tr.p0)), v));
            s += w * g.eval(th, ph) * std::sin(th);
        }
    return s * (t1 - t0) * (p1 - p0) / (m * m);
}

TEST(PortalSampling, SkyCellsFollowEquation2)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // A coarse table sky keeps the independent quadrature quick; refined in theta to 1 degree.
    test::SceneBuilder b;
    const int m = b.material("m", glm::vec3(0.5f));
    b.add("south", rect({1, 1, 4}, {1.5f, 0, 0}, {0, 1, 0}), m, PortalMark::Panes);
    b.add("skylight", rect({2, 3, 2}, {0.5f, 0, 0}, {0, 0, 0.5f}), m, PortalMark::Panes);
    b.add("tilted", rect({0.2f, 2.5f, 1}, {0.6f, 0, 0}, {0, 0.5f, 0.7f}), m, PortalMark::Panes);
    b.camera({1, 1.5, 1}, {2, 0, 2}, {0, 1, 0}, 60.0);
    Scene scene = b.build();
    const Goniogram g = tableSky({0, 30, 60, 90}, {0, 90, 180, 270, 360},
                                 {{800, 800, 800, 800, 800}, {600, 900, 1500, 700, 600},
                                  {300, 500, 1200, 400, 300}, {100, 150, 400, 120, 100}},
                                 "test");
    const SkyTables sky = makeSkyTables(g);
    const PortalEmission pe = setupPortalEmission(scene, sky, g, "", 8);
    ASSERT_EQ(pe.pSun, 0.0);
    // The table against the quadrature, cell by cell (cells cut by a portal plane use a coarser
    // rule in the table: 1 %; the others are exact: 1e-3).
    std::vector<double> expect(sky.cells);
    double total = 0.0;
    for (std::uint32_t i = 0; i + 1 < sky.thetaNodes; ++i)
        for (std::uint32_t j = 0; j + 1 < sky.phiNodes; ++j) {
            const std::uint32_t k = i * (sky.phiNodes - 1) + j;
            expect[k] = cellWeightByQuadrature(g, pe.portals, i, j);
            total += expect[k];
        }
    for (std::uint32_t k = 0; k < sky.cells; ++k)
        EXPECT_NEAR(pe.sources.probability(1 + k), expect[k] / total, 0.01 * expect[k] / total + 1e-9)
            << "cell " << k;
    // The device draws cells with the table: chi-square against the quadrature, cells binned by
    // the user's table cells (30 deg x 90 deg).
    const std::uint32_t n = 400000;
    cl::Kernel k(ctx->program("test_probes.cl"), "cdf_probe");
    cl::Buffer ab = ctx->buffer(CL_MEM_READ_ONLY, pe.sources.alias.size() * 4, "alias", pe.sources.alias.data());
    cl::Buffer out = ctx->buffer(CL_MEM_WRITE_ONLY, n * 4, "entries");
    ocl::setKernelArgs(k, ab, pe.sources.aliasShift, out, n, std::uint32_t{21});
    ocl::launch(*ctx, k, "cdf_probe", n);
    std::vector<std::uint32_t> got(n);
    ctx->queue().enqueueReadBuffer(out, CL_TRUE, 0, n * 4, got.data());
    auto bin = [&](std::uint32_t cell) {
        const std::uint32_t i = cell / (sky.phiNodes - 1), j = cell % (sky.phiNodes - 1);
        const double th = 0.5 * (g.theta()[i] + g.theta()[i + 1]), ph = 0.5 * (g.phi()[j] + g.phi()[j + 1]);
        return static_cast<int>(th / (M_PI / 6)) * 4 + static_cast<int>(ph / (M_PI / 2));
    };
    std::vector<double> obs(12, 0.0), exp(12, 0.0);
    for (auto e : got) {
        ASSERT_GE(e, 1u) << "the sun was drawn though it sends nothing";
        obs[static_cast<std::size_t>(bin(e - 1))] += 1.0;
    }
    for (std::uint32_t c = 0; c < sky.cells; ++c)
        exp[static_cast<std::size_t>(bin(c))] += n * expect[c] / total;
    EXPECT_GT(test::chiSquarePValue(obs, exp), kMinP);
}

// Luminances Y of the weights of n paths the portal strategy emits in `scene` (kernel
// portal_emit_probe), every candidate kept (*kept: all were).
std::vector<double> emittedLuminances(ocl::Context& ctx, const Scene& scene, const PortalEmission& pe,
                                      const SkyTables& sky, std::uint32_t overlap, std::uint32_t n, bool* kept)
{
    const dev::RenderParams p = test::emissionParams(scene, sky, 3);
    const dev::SourceParams sp = sourceParams(pe.sources, pe.sunWeight);
    dev::PortalParams pp{};
    pp.groups = static_cast<std::uint32_t>(pe.groups.size());
    pp.overlap = overlap;
    pp.group_alias_shift = pe.groupAliasShift;
    DeviceBvh pbvh(ctx, pe.bvh);
    auto buf = [&](const auto& v, const char* what) {
        return ctx.buffer(CL_MEM_READ_ONLY, v.size() * sizeof(v[0]), what, v.data());
    };
    cl::Buffer params = ctx.buffer(CL_MEM_READ_ONLY, sizeof p, "params", &p);
    cl::Buffer sourceParams = ctx.buffer(CL_MEM_READ_ONLY, sizeof sp, "source params", &sp);
    cl::Buffer portalParams = ctx.buffer(CL_MEM_READ_ONLY, sizeof pp, "portal params", &pp);
    cl::Buffer out = ctx.buffer(CL_MEM_WRITE_ONLY, std::size_t{n} * 16, "weights");
    cl::Kernel k(ctx.program("test_portal_probes.cl", {"FEN_BVH_WIDTH=8"}), "portal_emit_probe");
    // Named: clSetKernelArg does not keep a buffer alive.
    const cl::Buffer theta = buf(sky.theta, "theta"), phi = buf(sky.phi, "phi"),
                     values = buf(sky.values, "values"), factor = buf(pe.skyFactor, "factor"),
                     alias = buf(pe.sources.alias, "alias"),
                     groups = buf(pe.groups, "groups"), galias = buf(pe.groupAlias, "group alias"),
                     gratio = buf(pe.groupRatio, "group ratio"), cbin = buf(pe.cellBin, "cell bins"),
                     range = buf(pe.groupRange, "range"),
                     tcdf = buf(pe.triangleCdf, "tcdf"), verts = buf(pe.vertices, "verts");
    // The complement (PortalParams.complement) is 0: its `uniform` tables are bound but never read.
    ocl::setKernelArgs(k, params, sourceParams, alias, theta, phi, values, factor, portalParams, groups,
                       galias, gratio, cbin, range, tcdf, verts, pbvh.nodes(), pbvh.packets(), sourceParams,
                       alias, factor, out, n);
    ocl::launch(ctx, k, "portal_emit_probe", n);
    std::vector<cl_float4> w(n);
    ctx.queue().enqueueReadBuffer(out, CL_TRUE, 0, w.size() * 16, w.data());
    std::vector<double> y;
    *kept = true;
    for (const auto& x : w) {
        *kept = *kept && x.s[3] == 1.0f;
        y.push_back(luminance(x.s[0], x.s[1], x.s[2]));
    }
    return y;
}

// The luminous flux through a portal plane of area S and normal n, from both sides: the sun's
// E S |v_sun . n| and the sky's illuminance of either face (an independent quadrature of the
// goniogram).
double planeFlux(const Scene& scene, const Goniogram& g, double S, const glm::dvec3& n)
{
    return sunIlluminanceY_lux(scene) * S * std::fabs(glm::dot(scene.sun.travelDirection, n)) +
           S * (g.illuminance(n) + g.illuminance(-n));
}

TEST(PortalSampling, EmittedWeightsCarryTheFluxThroughThePortal)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // One vertical pane (no overlaps, N = 1): E[Y(weight)] is the luminous flux through it.
    test::SceneBuilder b;
    const int m = b.material("m", glm::vec3(0.5f));
    b.add("pane", rect({0, 1, 0}, {1.5f, 0, 0}, {0, 1.2f, 0}), m, PortalMark::Panes);
    b.add("floor", rect({-3, 0, -3}, {6, 0, 0}, {0, 0, 6}), m);
    const double alt = 30.0;
    b.sun(alt, 160.0, 40000.0);
    b.cieSky(8, 2500.0, alt, 160.0);
    b.camera({0, 1, 2}, {0, 1, 0}, {0, 1, 0}, 60.0);
    const Scene scene = b.build();
    const PortalTables t = portalTables(scene);
    bool kept = false;
    const auto ms = test::meanAndStdErr(emittedLuminances(*ctx, scene, t.pe, t.tables, FEN_OVERLAP_WEIGHT, 1u << 20, &kept));
    EXPECT_TRUE(kept) << "a single pane: every candidate is kept";
    const double flux = planeFlux(scene, *t.sky, 1.5 * 1.2, glm::dvec3(0, 0, 1));
    EXPECT_NEAR(ms.mean, flux, 4.0 * ms.se) << "relative se " << ms.se / ms.mean;
    EXPECT_NEAR(t.pe.sunFlux_lm + t.pe.skyFlux_lm, flux, 1e-3 * flux);
    EXPECT_LT(ms.se / ms.mean, 3e-3);
}

TEST(PortalSampling, EmittedWeightsCarryTheFluxThroughEveryPlane)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // Four planes of four orientations, the group chosen from a direction bin's table: with
    // every crossing counted (--portal-overlap none), E[Y(weight)] is the sum of the planes'
    // fluxes -- whatever P(g | bin), as long as the weight uses it (4 sigma).
    const Scene scene = portalScene();
    const PortalTables t = portalTables(scene);
    ASSERT_EQ(t.pe.portals.groups.size(), 4u);
    ASSERT_GT(t.pe.groupRatio.size(), 4u * 2u) << "the sun's bin and at least one sky bin";
    bool kept = false;
    const auto ms = test::meanAndStdErr(emittedLuminances(*ctx, scene, t.pe, t.tables, FEN_OVERLAP_NONE, 1u << 21, &kept));
    EXPECT_TRUE(kept);
    double flux = 0.0;
    for (const PortalGroup& grp : t.pe.portals.groups)
        flux += planeFlux(scene, *t.sky, grp.area_m2, grp.normal);
    EXPECT_NEAR(ms.mean, flux, 4.0 * ms.se) << "relative se " << ms.se / ms.mean;
    EXPECT_LT(ms.se / ms.mean, 3e-3);
}

TEST(PortalSampling, OnePlaneNeedsNoCount)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // Portals in one plane (a window of 3 x 2 panes, shared edges and corners included): every
    // emitted line crosses exactly one portal triangle, so the portal strategy skips counting
    // N(x, v) there (PortalSet::singlePlane). Rejection with the count must then keep every
    // candidate and give the weights emission without it gives, bit for bit.
    test::SceneBuilder b;
    const int m = b.material("m", glm::vec3(0.5f));
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 2; ++j)
            b.add(cat("pane", i, j), rect({0.5f * static_cast<float>(i), 1 + 0.6f * static_cast<float>(j), 0},
                                         {0.5f, 0, 0}, {0, 0.6f, 0}),
                  m, PortalMark::Panes);
    b.add("floor", rect({-3, 0, -3}, {6, 0, 0}, {0, 0, 6}), m);
    b.sun(35.0, 150.0, 40000.0);
    b.cieSky(8, 2500.0, 35.0, 150.0);
    b.camera({0, 1, 2}, {0, 1, 0}, {0, 1, 0}, 60.0);
    const Scene scene = b.build();
    const PortalTables t = portalTables(scene);
    ASSERT_TRUE(t.pe.portals.singlePlane());
    bool keptCounted = false, keptSkipped = false;
    const auto counted = emittedLuminances(*ctx, scene, t.pe, t.tables, FEN_OVERLAP_REJECT, 1u << 18, &keptCounted);
    const auto skipped = emittedLuminances(*ctx, scene, t.pe, t.tables, FEN_OVERLAP_NONE, 1u << 18, &keptSkipped);
    EXPECT_TRUE(keptCounted) << "a line crossed two triangles of one plane";
    EXPECT_TRUE(keptSkipped);
    EXPECT_EQ(counted, skipped);
}

TEST(PortalSampling, OverlapCountsEveryPortalOnTheLine)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // N(x, v): three stacked panes; a pane listed twice (two identical triangles: both count);
    // a single triangle alone in a leaf (its packet's padding lanes repeat it: counts once).
    std::vector<Triangle> tris;
    for (float z : {0.0f, 0.5f, 1.0f})
        for (const auto& t : rect({0, 0, z}, {1, 0, 0}, {0, 1, 0}))
            tris.push_back(t);
    const Triangle twin{{3, 0, 0}, {4, 0, 0}, {3, 1, 0}};
    tris.push_back(twin);
    tris.push_back(twin);
    tris.push_back({{10, 0, 0}, {11, 0, 0}, {10, 1, 0}});
    const FlatBvh bvh = flattenBvh(buildBinnedSah(tris), tris, 8);
    DeviceBvh dev(*ctx, bvh);
    const std::vector<dev::Ray> rays = {
        test::toDevice(test::refRay({0.3f, 0.2f, -5}, {0, 0, 1})),            // all three panes
        test::toDevice(test::refRay({0.3f, 0.2f, 0.75f}, {0, 0, 1})),         // the last one only
        test::toDevice(test::refRay({3.2f, 0.2f, -5}, {0, 0, 1})),            // the twins
        test::toDevice(test::refRay({10.2f, 0.2f, -5}, {0, 0, 1})),           // the lone triangle
        test::toDevice(test::refRay({5, 5, -5}, {0, 0, 1})),                  // nothing
        test::toDevice(test::refRay({0.3f, 0.2f, -5}, {0.01f, 0.02f, 1})),    // slanted, three
    };
    const std::vector<std::uint32_t> expect = {3, 1, 2, 1, 0, 3};
    const auto n = static_cast<std::uint32_t>(rays.size());
    cl::Kernel k(ctx->program("test_portal_probes.cl", {"FEN_BVH_WIDTH=8"}), "count_probe");
    cl::Buffer rb = ctx->buffer(CL_MEM_READ_ONLY, n * sizeof(dev::Ray), "rays", rays.data());
    cl::Buffer out = ctx->buffer(CL_MEM_WRITE_ONLY, n * 4, "counts");
    ocl::setKernelArgs(k, dev.nodes(), dev.packets(), rb, out, n);
    ocl::launch(*ctx, k, "count_probe", n);
    std::vector<std::uint32_t> got(n);
    ctx->queue().enqueueReadBuffer(out, CL_TRUE, 0, n * 4, got.data());
    for (std::uint32_t i = 0; i < n; ++i)
        EXPECT_EQ(got[i], expect[i]) << "ray " << i;
}

}  // namespace
}  // namespace fen
