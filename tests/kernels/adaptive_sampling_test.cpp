// adaptive_sampling_test.cpp — the adaptive strategy's emission against the density it claims
// (DESIGN.md §3.3): from a known grid (probabilities set by the test, far from the base density)
// the device picks cells, and the sixteen parts of each, with exactly those probabilities (chi-square, p > 1e-3,
// fixed seeds), and every path's weight is the emitted radiance over the exact density, so the
// mean weight is the luminous flux through the emission disk (4 sigma of the sample's standard
// error) -- over a `uniform` base, and over a `portal` base, where disk lines that cross a portal
// are rejected and the portal cells emit them: the partition is exact only if that mean still
// holds.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "cl/launch.h"
#include "emission/adaptive_strategy.h"
#include "emission/emission_sphere.h"
#include "emission/light_levels.h"
#include "io/image.h"
#include "sky/sky_spec.h"
#include "support/cl_fixture.h"
#include "support/emit_probe.h"
#include "support/render_support.h"
#include "support/statistics.h"

namespace fen {
namespace {

using test::rect;

constexpr double kMinP = 1e-3;

// A floor, a pane marked as a portal, the sun and a CIE sky.
Scene paneScene()
{
    test::SceneBuilder b;
    const int m = b.material("m", glm::vec3(0.5f));
    b.add("floor", rect({-3, 0, -3}, {6, 0, 0}, {0, 0, 6}), m);
    b.add("pane", rect({-0.5f, 1, 0}, {1.5f, 0, 0}, {0, 1.2f, 0}), m, PortalMark::Panes);
    b.sun(35.0, 160.0, 40000.0);
    b.cieSky(8, 2500.0, 35.0, 160.0);
    b.camera({0, 1, 2}, {0, 1, 0}, {0, 1, 0}, 60.0);
    return b.build();
}

struct Probe {
    std::vector<cl_float4> beta, org, dir;
    double flux_lm = 0.0;  // E_Y pi R^2 + pi R^2 ∫ g dw: what the mean weight must be
    std::vector<double> realised;
};

// Emits n paths with the adaptive strategy over `base`, its probabilities set to `shape` of the
// cell index (when given).
Probe emitPaths(ocl::Context& ctx, const Scene& scene, EmissionMethod base, std::uint32_t n,
                double (*shape)(std::size_t))
{
    const auto g = buildSky(scene);
    const SkyTables tables = makeSkyTables(g);
    const DeviceSky sky(ctx, tables);
    EmissionSettings s;
    s.method = EmissionMethod::Adaptive;
    s.adaptive.base = base;
    s.adaptive.initialSkyDepth = 1;
    s.adaptive.initialDepth = 1;
    const double fixedScale = std::ldexp(1.0, 40) / referenceLuminance(scene, tables);
    auto strategy = makeAdaptiveStrategy(s, {ctx, scene, tables, g, sky, 8, fixedScale});
    if (shape) {
        std::vector<double> p(strategy->grid().cells().size());
        for (std::size_t i = 0; i < p.size(); ++i)
            p[i] = shape(i);
        strategy->setProbabilities(p);
    }
    Probe out;
    out.realised = strategy->realisedProbabilities();

    const dev::RenderParams params = test::emissionParams(scene, tables, 5);
    glm::dvec3 centre;
    double radius;
    emissionSphere(scene, &centre, &radius);
    out.flux_lm = M_PI * radius * radius * (sunIlluminanceY_lux(scene) + tables.integral_cd_m2_sr);
    cl::Kernel k(ctx.program("test_adaptive_probes.cl", {"FEN_BVH_WIDTH=8"}), "adaptive_emit_probe");
    test::EmittedPaths e = test::runEmitProbe(ctx, k, "adaptive_emit_probe", *strategy, params, n);
    out.beta = std::move(e.beta);
    out.org = std::move(e.org);
    out.dir = std::move(e.dir);
    return out;
}

std::uint32_t quarterOf(const cl_float4& beta)
{
    std::uint32_t q;
    std::memcpy(&q, &beta.s[3], 4);
    return q;
}

// Far from the base density: heavy and light cells side by side.
double unevenShape(std::size_t i) { return 1.0 + static_cast<double>((i * 7) % 5) * (i % 3 == 0 ? 10.0 : 1.0); }

TEST(AdaptiveSampling, CellsAndTheirPartsFollowTheGrid)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const std::uint32_t n = 1u << 20;
    const Probe p = emitPaths(*ctx, paneScene(), EmissionMethod::Uniform, n, unevenShape);
    const std::size_t cells = p.realised.size();
    ASSERT_GE(cells, 16u);
    std::vector<double> obs(16 * cells, 0.0), exp(16 * cells, 0.0);
    for (const auto& b : p.beta) {
        const std::uint32_t q = quarterOf(b);
        ASSERT_LT(q, obs.size());
        obs[q] += 1.0;
    }
    for (std::size_t c = 0; c < cells; ++c)
        for (int q = 0; q < 16; ++q)
            exp[16 * c + q] = n * p.realised[c] / 16.0;
    EXPECT_GT(test::chiSquarePValue(obs, exp), kMinP);
}

// E[Y(weight)] over all candidates (a rejected one weighs 0) = the flux through the disk, whatever
// the grid's probabilities: the weights carry the exact density.
void expectMeanWeightIsTheFlux(const Probe& p, const char* what)
{
    std::vector<double> y;
    y.reserve(p.beta.size());
    for (const auto& b : p.beta)
        y.push_back(luminance(b.s[0], b.s[1], b.s[2]));
    const auto ms = test::meanAndStdErr(y);
    std::printf("[ adaptive ] %s: mean weight %.6g +- %.3g lm, flux %.6g lm (%+.2f sigma)\n", what,
                ms.mean, ms.se, p.flux_lm, (ms.mean - p.flux_lm) / ms.se);
    EXPECT_NEAR(ms.mean, p.flux_lm, 4.0 * ms.se) << what;
    EXPECT_LT(ms.se, 0.01 * p.flux_lm) << what << ": too noisy to mean anything";
}

TEST(AdaptiveSampling, WeightsCarryTheExactDensityOverUniform)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const Probe p = emitPaths(*ctx, paneScene(), EmissionMethod::Uniform, 1u << 21, unevenShape);
    expectMeanWeightIsTheFlux(p, "uniform base, uneven grid");
    const Probe b = emitPaths(*ctx, paneScene(), EmissionMethod::Uniform, 1u << 21, nullptr);
    expectMeanWeightIsTheFlux(b, "uniform base, base grid");
}

TEST(AdaptiveSampling, TheGroundsLightTravelsUpFromTheWholeDisk)
{
    // With the ground's glow the grid's sky boxes also cover s in [1, 2), the lower hemisphere;
    // its paths travel upwards, their origins uniform on the disk of radius R orthogonal to the
    // direction and 1 % beyond the sphere (travel_basis mirrored there: Duff's frame is singular
    // at +y). The mean weight is the flux through the disk, the ground's included.
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    Scene scene = paneScene();
    scene.sky.groundAlbedo = 0.3;
    expectMeanWeightIsTheFlux(emitPaths(*ctx, scene, EmissionMethod::Uniform, 1u << 21, unevenShape),
                              "uniform base with a ground, uneven grid");
    // The base grid: every origin box of a direction box equally likely, so origins uniform on the disk.
    const Probe p = emitPaths(*ctx, scene, EmissionMethod::Uniform, 1u << 20, nullptr);
    glm::dvec3 centre;
    double radius;
    emissionSphere(scene, &centre, &radius);
    constexpr int kBins = 20;
    std::vector<double> obs(kBins, 0.0), exp(kBins, 0.0);
    std::size_t up = 0;
    for (std::size_t i = 0; i < p.beta.size(); ++i) {
        const glm::dvec3 o(p.org[i].s[0], p.org[i].s[1], p.org[i].s[2]), d(p.dir[i].s[0], p.dir[i].s[1], p.dir[i].s[2]);
        if (!(d.y > 0.0))
            continue;
        ++up;
        const glm::dvec3 r = o - centre;
        const double along = glm::dot(r, d);
        const double perp2 = glm::dot(r, r) - along * along;
        ASSERT_NEAR(along, -1.01 * radius, 1e-4 * radius) << "path " << i;
        ASSERT_LE(perp2, radius * radius * (1.0 + 1e-4)) << "path " << i;
        obs[std::min(kBins - 1, static_cast<int>(perp2 / (radius * radius) * kBins))] += 1.0;
    }
    ASSERT_GT(up, p.beta.size() / 20) << "the ground's cells must be drawn";
    for (double& e : exp)
        e = static_cast<double>(up) / kBins;  // uniform on a disk: r^2 uniform
    EXPECT_GT(test::chiSquarePValue(obs, exp), kMinP);
}

TEST(AdaptiveSampling, TheDisksBasisIsOrthonormalForEveryDirectionOfTravel)
{
    // The ground's light travels upwards, where Duff's frame (continuous for the sky's downward
    // light) divides by 1 - n.y: straight up it is 0/0, just off it digits are lost. The mirrored
    // frame keeps (t1, t2, n) orthonormal to float precision in every direction, and downward
    // directions keep the frame they had.
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    std::vector<cl_float4> dirs;
    const auto add = [&](glm::dvec3 d) {
        d = glm::normalize(d);
        dirs.push_back({{float(d.x), float(d.y), float(d.z), 0.0f}});
    };
    for (double y : {1.0, -1.0})
        add({0, y, 0});
    for (double eps : {1e-7, 1e-5, 1e-3, 0.1})
        for (double y : {1.0, -1.0}) {
            add({eps, y, 0});
            add({0, y, -eps});
            add({-eps, y, eps});
        }
    for (int k = 0; k < 1000; ++k)  // a spiral over the sphere
        add(skyDirection(std::acos(1.0 - 2.0 * (k + 0.5) / 1000), 2.39996323 * k));
    const auto n = static_cast<std::uint32_t>(dirs.size());
    cl::Kernel k(ctx->program("test_adaptive_probes.cl", {"FEN_BVH_WIDTH=8"}), "travel_basis_probe");
    cl::Buffer in = ctx->buffer(CL_MEM_READ_ONLY, n * 16, "directions", dirs.data());
    cl::Buffer out = ctx->buffer(CL_MEM_WRITE_ONLY, 2 * n * 16, "bases");
    ocl::setKernelArgs(k, in, out, n);
    ocl::launch(*ctx, k, "travel_basis_probe", n);
    std::vector<cl_float4> b(2 * n);
    ctx->queue().enqueueReadBuffer(out, CL_TRUE, 0, b.size() * 16, b.data());
    const auto v = [](const cl_float4& f) { return glm::dvec3(f.s[0], f.s[1], f.s[2]); };
    for (std::uint32_t i = 0; i < n; ++i) {
        const glm::dvec3 d = v(dirs[i]), t1 = v(b[2 * i]), t2 = v(b[2 * i + 1]);
        SCOPED_TRACE(testing::Message() << "direction " << d.x << " " << d.y << " " << d.z);
        EXPECT_NEAR(glm::length(t1), 1.0, 1e-5);
        EXPECT_NEAR(glm::length(t2), 1.0, 1e-5);
        EXPECT_NEAR(glm::dot(t1, t2), 0.0, 1e-5);
        EXPECT_NEAR(glm::dot(t1, d), 0.0, 1e-5);
        EXPECT_NEAR(glm::dot(t2, d), 0.0, 1e-5);
    }
}

TEST(AdaptiveSampling, PortalCellsAndRejectedDiskLinesPartitionTheRays)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const Probe p = emitPaths(*ctx, paneScene(), EmissionMethod::Portal, 1u << 21, unevenShape);
    expectMeanWeightIsTheFlux(p, "portal base, uneven grid");
    // Kept portal-cell paths start on the line through the pane: their origin + t dir crosses the
    // plane z = 0 inside the pane.
    std::size_t kept = 0, rejected = 0, onPane = 0;
    const Scene scene = paneScene();
    for (std::size_t i = 0; i < p.beta.size(); ++i) {
        if (p.org[i].s[3] == 0.0f) {
            ++rejected;
            continue;
        }
        ++kept;
        const glm::dvec3 o(p.org[i].s[0], p.org[i].s[1], p.org[i].s[2]), d(p.dir[i].s[0], p.dir[i].s[1], p.dir[i].s[2]);
        if (std::fabs(d.z) < 1e-6)
            continue;
        const glm::dvec3 x = o + (-o.z / d.z) * d;
        onPane += x.x >= -0.5 - 1e-3 && x.x <= 1.0 + 1e-3 && x.y >= 1.0 - 1e-3 && x.y <= 2.2 + 1e-3;
    }
    EXPECT_GT(rejected, 0u) << "disk lines through the pane must be rejected";
    EXPECT_GT(onPane, kept / 20) << "the portal cells must put paths through the pane";
}

}  // namespace
}  // namespace fen
