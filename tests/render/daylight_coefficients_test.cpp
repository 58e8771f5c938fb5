// daylight_coefficients_test.cpp — daylight coefficients (DESIGN.md §8; host/annual/sky_patches.h,
// kernels/lib/sky_patch.h) against closed forms and against rendering a sky directly:
//   - unobstructed sensors under a sky of 1 cd/m^2: a horizontal one sees each sky patch's projected
//     solid angle and no ground, a vertical one facing east each patch's cosine-weighted solid angle
//     on its side (by quadrature) and the ground's pi/2; all of it direct light;
//   - in a room with a south and an east window: the matrix times a CIE clear sky's patch vector
//     (adaptive emission learning for the unit sky, and for that sky) against a render under that sky, cell by cell within 4 sigma of the two estimates' noise plus
//     the discretisation's bound sum_p D[s][p] (max_p L - min_p L) (the sky's luminance spread over
//     each patch, which the patch vector takes as constant);
//   - the kernel forms add the same coefficients, bit for bit.
// The chi-squares scale each z^2 by 13/15 (t with 15 degrees of freedom: 16 batches) and ask p > 1e-4.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "annual/sky_patches.h"
#include "sensor/sensor_set.h"
#include "sky/sky_spec.h"
#include "support/cl_fixture.h"
#include "support/render_support.h"
#include "support/statistics.h"
#include "support/window_rooms.h"
#include "util/error.h"

namespace fen {
namespace {

using test::rect;

struct Coefficients {
    RenderResult r;
    std::vector<double> D, se;  // 3 x cells x patches: all light, direct, indirect
    std::size_t cells = 0, patches = 0;
};

// Renders `scene`'s sensors with every path tagged by its Reinhart patch (MF mf).
Coefficients renderCoefficients(ocl::Context& ctx, Scene scene, const SensorSet& set, std::uint64_t paths, int mf,
                                EmissionMethod method = EmissionMethod::Uniform,
                                std::optional<KernelMode> kernels = std::nullopt, std::uint32_t seed = 1,
                                const std::vector<double>& patchWeights = {})
{
    scene.bounds.grow(sensorBounds(set));
    const auto t = test::renderScene(ctx, scene, 8, 8, paths, {Roi{0, 0, 8, 8}}, seed, 1024, [&](RenderSettings& s) {
        s.sensors = &set;
        s.noImage = true;
        s.emission.method = method;
        s.kernels = kernels;
        s.skyPatchMF = mf;
        s.skyPatchWeights = patchWeights;
    });
    Coefficients c{t.result, {}, {}, set.cells.size(), skyPatchCount(mf)};
    EXPECT_TRUE(c.r.daylightCoefficients.has_value());
    if (c.r.daylightCoefficients) {
        c.D = c.r.daylightCoefficients->mean();
        c.se = c.r.daylightCoefficients->stdErr();
    }
    EXPECT_EQ(c.D.size(), 3 * c.cells * c.patches);
    EXPECT_EQ(c.r.counts.badContributions, 0u);
    EXPECT_EQ(c.r.counts.overflows, 0u);
    return c;
}

// A sky of 1 cd/m^2 above and (albedo 1 of pi lux) about 1 cd/m^2 below; returns the ground's exact value.
double unitSkyAndGround(Scene& scene)
{
    scene.sun.present = false;
    scene.sky = SkySpec{};
    scene.sky.type = SkySpec::Type::Uniform;
    scene.sky.luminance_cd_m2 = 1.0;
    scene.sky.groundAlbedo = 1.0;
    return buildSky(scene)->groundLuminance();
}

// Chi-square of row `cell` of matrix `block` (0 all light, 1 direct) against `expected` over the
// patches where expected > 0; entries expected to be 0 must be exactly 0.
void expectRow(const Coefficients& c, std::size_t block, std::size_t cell, const std::vector<double>& expected,
               const char* what)
{
    const std::size_t base = (block * c.cells + cell) * c.patches;
    double chi2 = 0.0, worst = 0.0;
    int k = 0;
    for (std::size_t p = 0; p < c.patches; ++p) {
        const double d = c.D[base + p], s = c.se[base + p];
        if (expected[p] < 1e-12) {
            EXPECT_EQ(d, 0.0) << what << ": patch " << p << " sees nothing";
            continue;
        }
        ASSERT_GT(s, 0.0) << what << ": patch " << p << " saw no spread";
        const double z = (d - expected[p]) / s;
        chi2 += z * z * 13.0 / 15.0;
        worst = std::max(worst, std::abs(z));
        ++k;
    }
    const double pv = test::gammaQ(0.5 * k, 0.5 * chi2);
    std::printf("[ coeffs   ] %s: %d patches, chi2 %.1f, p %.3g, worst %.2f sigma\n", what, k, chi2, pv, worst);
    EXPECT_GT(pv, 1e-4) << what;
}

// Over patch k: the integral of max(0, w . n) dw, by a 64 x 64 midpoint rule in (sin altitude, azimuth).
double cosineOverPatch(const SkyPatch& p, const glm::dvec3& n)
{
    const double d = M_PI / 180.0, s0 = std::sin(p.altLoDeg * d), s1 = std::sin(p.altHiDeg * d);
    double sum = 0.0;
    for (int i = 0; i < 64; ++i) {
        const double s = s0 + (s1 - s0) * (i + 0.5) / 64, c = std::sqrt(1.0 - s * s);
        for (int j = 0; j < 64; ++j) {
            const double a = (p.aziCentreDeg + p.aziWidthDeg * ((j + 0.5) / 64 - 0.5)) * d;
            sum += std::max(0.0, glm::dot(glm::dvec3(c * std::sin(a), s, -c * std::cos(a)), n));
        }
    }
    return sum / (64 * 64) * p.solidAngle_sr;
}

TEST(DaylightCoefficients, UnobstructedSensorsSeeEachPatchsCosineWeightedSolidAngle)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // A speck of geometry behind the sensors stands for the scene; one 2 x 2 m cell facing up and
    // one facing east (+x), apart.
    test::SceneBuilder b;
    b.add("speck", {{{-3, 0, -0.5f}, {-2.99f, 0, -0.5f}, {-3, 0.01f, -0.5f}}}, b.material("black", glm::vec3(0.0f)));
    b.uniformSky(1.0);
    b.camera({0, 3, 4}, {0, 0, 0}, {0, 1, 0}, 40.0);
    Scene scene = b.build();
    const double Lg = unitSkyAndGround(scene);
    SensorSet set;
    addMeshSensor(set, "up", "node", "plate up", rect({-1, 1, 1}, {2, 0, 0}, {0, 0, -2}), 2.0);
    addMeshSensor(set, "east", "node", "plate east", rect({3, 0, 1}, {0, 0, -2}, {0, 2, 0}), 2.0);
    ASSERT_EQ(set.cells.size(), 2u);
    const int mf = 1;
    const Coefficients c = renderCoefficients(*ctx, scene, set, 8u << 20, mf);
    const std::vector<SkyPatch> patches = skyPatches(mf);
    std::vector<double> up = patchProjectedSolidAngles(mf), east(patches.size());
    up[0] = 0.0;
    for (std::size_t p = 1; p < patches.size(); ++p)
        east[p] = cosineOverPatch(patches[p], glm::dvec3(1.0, 0.0, 0.0));
    east[0] = 0.5 * M_PI * Lg;  // the ground's half of the cosine over the lower hemisphere, at L_g
    const std::size_t upCell = set.cells[0].normal.y > 0.5 ? 0 : 1, eastCell = 1 - upCell;
    expectRow(c, 0, upCell, up, "facing up, all light");
    expectRow(c, 0, eastCell, east, "facing east, all light");
    // Nothing scatters light on to them (the speck is black): all of it is direct.
    for (std::size_t k = 0; k < c.cells * c.patches; ++k)
        ASSERT_EQ(c.D[k], c.D[c.cells * c.patches + k]) << "entry " << k;
    // Each row sums to the sensor's illuminance under that sky.
    const std::vector<double> E = c.r.sensors->mean();
    for (std::size_t s = 0; s < 2; ++s) {
        double sum = 0.0;
        for (std::size_t p = 0; p < c.patches; ++p)
            sum += c.D[s * c.patches + p];
        EXPECT_NEAR(sum, E[s], 1e-9 * E[s]);
    }
}

// Learning for the unit sky, and for the very sky the matrix is then multiplied by (what an annual
// study does with the year's mean sky: RenderSettings::skyPatchWeights): either way unbiased.
class MatrixTimesASky : public ::testing::TestWithParam<bool> {};

TEST_P(MatrixTimesASky, AgreesWithRenderingThatSky)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const bool weighted = GetParam();
    // The room with a south and an east window (glass, grey walls): a work plane of 36 cells at
    // 0.8 m. The sky: CIE clear (type 12) with the sun (left out: sky only) in the south-east at
    // 35 degrees, over a ground of albedo 0.2.
    Scene direct = test::windowRoom(test::Windows::Two);
    Scene unit = direct;
    unitSkyAndGround(unit);
    SensorSet set;
    addMeshSensor(set, "plane", "node", "work plane", rect({0, 0.8f, 3}, {3, 0, 0}, {0, 0, -3}), 0.5);
    ASSERT_EQ(set.cells.size(), 36u);
    const int mf = 2;
    direct.sun.present = false;
    direct.sky = SkySpec{};
    direct.sky.type = SkySpec::Type::Cie;
    direct.sky.cieType = 12;
    direct.sky.zenithLuminance_cd_m2 = 4000.0;
    direct.sky.sunAltitudeDeg = 35.0;
    direct.sky.sunAzimuthDeg = 135.0;
    direct.sky.groundAlbedo = 0.2;
    const std::optional<Goniogram> sky = buildSky(direct);
    ASSERT_TRUE(sky);
    const std::vector<double> v = patchLuminance(&*sky, mf);
    std::vector<double> weights;
    if (weighted) {
        // the sky's patches, scaled to the unit sky's horizontal illuminance (annualPatchWeights)
        const std::vector<double> proj = patchProjectedSolidAngles(mf);
        double h = 0.0;
        for (std::size_t p = 0; p < v.size(); ++p)
            h += v[p] * proj[p];
        for (double x : v)
            weights.push_back(std::max(x, 1e-3) * M_PI / h);
    }
    const Coefficients c = renderCoefficients(*ctx, unit, set, 16u << 20, mf, EmissionMethod::Adaptive, std::nullopt, 1,
                                              weights);
    // Each patch's luminance spread (16 x 16 points), the ground's none.
    const std::vector<SkyPatch> patches = skyPatches(mf);
    std::vector<double> spread(patches.size(), 0.0);
    for (std::size_t p = 1; p < patches.size(); ++p) {
        double lo = INFINITY, hi = 0.0;
        const double d = M_PI / 180.0;
        for (int i = 0; i <= 16; ++i)
            for (int j = 0; j <= 16; ++j) {
                const double alt = (patches[p].altLoDeg + (patches[p].altHiDeg - patches[p].altLoDeg) * i / 16) * d;
                const double a = (patches[p].aziCentreDeg + patches[p].aziWidthDeg * (j / 16.0 - 0.5)) * d;
                const double L = sky->evalDirection({std::cos(alt) * std::sin(a), std::sin(alt), -std::cos(alt) * std::cos(a)});
                lo = std::min(lo, L);
                hi = std::max(hi, L);
            }
        spread[p] = hi - lo;
    }
    direct.bounds.grow(sensorBounds(set));
    const auto t = test::renderScene(*ctx, direct, 8, 8, 16u << 20, {Roi{0, 0, 8, 8}}, 7, 1024, [&](RenderSettings& s) {
        s.sensors = &set;
        s.noImage = true;
        s.emission.method = EmissionMethod::Adaptive;
    });
    ASSERT_TRUE(t.result.sensors);
    const std::vector<double> E = t.result.sensors->mean(), Ese = t.result.sensors->stdErr();
    double sumDc = 0.0, sumDirect = 0.0, worstBound = 0.0, chi2 = 0.0;
    for (std::size_t s = 0; s < set.cells.size(); ++s) {
        double e = 0.0, var = 0.0, bound = 0.0;
        for (std::size_t p = 0; p < c.patches; ++p) {
            const double D = c.D[s * c.patches + p], se = c.se[s * c.patches + p];
            e += D * v[p];
            var += se * se * v[p] * v[p];
            bound += D * spread[p];
        }
        const double sigma = std::sqrt(var + Ese[s] * Ese[s]);
        const double z = (e - E[s]) / sigma;
        chi2 += z * z * 13.0 / 15.0;
        EXPECT_LE(std::abs(e - E[s]), 4.0 * sigma + bound)
            << "cell " << s << ": matrix " << e << " lux, render " << E[s] << " (sigma " << sigma << ", bound " << bound << ")";
        worstBound = std::max(worstBound, bound / E[s]);
        sumDc += e;
        sumDirect += E[s];
    }
    std::printf("[ coeffs   ] CIE clear sky, MF %d, learnt for %s: matrix mean %.5g lux, render %.5g (%+.2f %%); chi2 %.1f "
                "over %zu cells; largest bound %.1f %% of a cell\n", mf, weighted ? "that sky" : "the unit sky", sumDc / 36,
                sumDirect / 36, 100.0 * (sumDc / sumDirect - 1.0), chi2, set.cells.size(), 100.0 * worstBound);
}

INSTANTIATE_TEST_SUITE_P(Learning, MatrixTimesASky, ::testing::Values(false, true),
                         [](const auto& info) { return std::string(info.param ? "ForThatSky" : "ForTheUnitSky"); });

TEST(DaylightCoefficients, KernelFormsAddTheSameCoefficients)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    Scene scene = test::windowRoom(test::Windows::Two);
    unitSkyAndGround(scene);
    SensorSet set;
    addMeshSensor(set, "plane", "node", "work plane", rect({0, 0.8f, 3}, {3, 0, 0}, {0, 0, -3}), 1.0);
    const Coefficients f = renderCoefficients(*ctx, scene, set, 1u << 20, 1, EmissionMethod::Adaptive, KernelMode::Fused);
    const Coefficients w = renderCoefficients(*ctx, scene, set, 1u << 20, 1, EmissionMethod::Adaptive, KernelMode::Wavefront);
    ASSERT_EQ(f.D.size(), w.D.size());
    for (std::size_t k = 0; k < f.D.size(); ++k)
        ASSERT_EQ(f.D[k], w.D[k]) << "entry " << k;
    double direct = 0.0, all = 0.0;
    for (std::size_t k = 0; k < f.cells * f.patches; ++k) {
        all += f.D[k];
        direct += f.D[f.cells * f.patches + k];
        ASSERT_LE(f.D[f.cells * f.patches + k], f.D[k] * (1.0 + 1e-12) + 1e-300) << "direct light above all light, entry " << k;
    }
    EXPECT_GT(direct, 0.0);
    EXPECT_LT(direct, all);  // the walls and floor reflect light on to the plane
}

}  // namespace
}  // namespace fen
