// sensor_test.cpp — sensor grids against closed forms (DESIGN.md §8): unobstructed sensors under a
// uniform sky, the CIE overcast sky and the sun; a vertical sensor; each cell of a floor under a
// ceiling opening, by every emission strategy and both kernel forms; a sensor above a white
// Lambertian floor against the floor's luminance in the image (L = rho E / pi); the daylight
// factor of an unobstructed sensor; an image bit-identical with and without sensors (they block
// nothing), and sensor sums bit-identical between the kernel forms.
// Tolerances: a grid mean within 4 standard errors (the jackknife over 16 batches); all cells of a
// grid together by a chi-square of their z-scores (each z from its own batch spread, t with 15
// degrees of freedom, so z^2 is scaled by 13/15 to mean 1) at p > 1e-4.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "io/image.h"
#include "sensor/points_file.h"
#include "sensor/sensor_set.h"
#include "sky/sky_spec.h"
#include "support/cl_fixture.h"
#include "support/render_support.h"
#include "support/statistics.h"
#include "util/error.h"

namespace fen {
namespace {

using test::rect;

constexpr double kSigmas = 4.0;

struct SensorRun {
    RenderResult r;
    std::vector<double> mean, se;
};

// Renders `scene` (bounds grown to the sensors, as the render command does) with `paths` paths.
SensorRun renderSensors(ocl::Context& ctx, Scene scene, const SensorSet& set, std::uint64_t paths,
                        EmissionMethod method = EmissionMethod::Uniform,
                        std::optional<KernelMode> kernels = std::nullopt, bool noImage = true)
{
    scene.bounds.grow(sensorBounds(set));
    const auto t = test::renderScene(ctx, scene, 32, 24, paths, {Roi{0, 0, 32, 24}}, 1, 1024,
                                     [&](RenderSettings& s) {
                                         s.sensors = &set;
                                         s.noImage = noImage;
                                         s.emission.method = method;
                                         s.kernels = kernels;
                                     });
    SensorRun run{t.result, {}, {}};
    EXPECT_TRUE(run.r.sensors.has_value());
    if (run.r.sensors) {
        run.mean = run.r.sensors->mean();
        run.se = run.r.sensors->stdErr();
    }
    EXPECT_EQ(run.r.counts.badContributions, 0u);
    EXPECT_EQ(run.r.counts.overflows, 0u);
    // the openings' share raced, adaptive's default, is off with no image (no pane to start a walk
    // on), in a render built without the command line too
    if (method == EmissionMethod::Adaptive && noImage) {
        EXPECT_EQ(run.r.emission["openings_share_auto"], false);
        EXPECT_EQ(run.r.emission["openings_race"]["phase"], "fixed");
    }
    return run;
}

// The area-weighted grid mean against `expected` within 4 sigma (jackknife), sigma <= maxRel.
void expectGridMean(const SensorRun& run, const SensorSet& set, double expected, double maxRel, const char* what)
{
    const auto e = run.r.sensors->jackknife([&](const std::vector<double>& E) {
        double s = 0.0, a = 0.0;
        for (std::size_t c = 0; c < E.size(); ++c) {
            const double area = set.cells[c].side_m * set.cells[c].side_m;
            s += area * E[c];
            a += area;
        }
        return s / a;
    });
    std::printf("[ sensors  ] %s: measured %.6g lux, expected %.6g, se %.3g (%.2f%%), %+.2f sigma\n", what, e.value,
                expected, e.stdErr, 100.0 * e.stdErr / expected, (e.value - expected) / e.stdErr);
    EXPECT_NEAR(e.value, expected, kSigmas * e.stdErr) << what;
    EXPECT_LE(e.stdErr, maxRel * expected) << what << ": too noisy to test";
}

// Every cell against its own expected value: the chi-square of the z-scores.
void expectCells(const SensorRun& run, const std::vector<double>& expected, const char* what)
{
    double chi2 = 0.0, worst = 0.0;
    for (std::size_t c = 0; c < expected.size(); ++c) {
        ASSERT_GT(run.se[c], 0.0) << what << ": cell " << c << " saw no spread";
        const double z = (run.mean[c] - expected[c]) / run.se[c];
        chi2 += z * z * 13.0 / 15.0;
        worst = std::max(worst, std::abs(z));
    }
    const double k = static_cast<double>(expected.size());
    const double p = test::gammaQ(0.5 * k, 0.5 * chi2);
    std::printf("[ sensors  ] %s: %zu cells, chi2 %.1f, p %.3g, worst %.2f sigma\n", what, expected.size(), chi2, p,
                worst);
    EXPECT_GT(p, 1e-4) << what << ": chi2 " << chi2 << " over " << k << " cells";
}

// An upward-facing 2 x 2 m sensor at height y (cells of 0.5 m) over a black ground.
SensorSet horizontalSensor(float y, double cell = 0.5)
{
    SensorSet set;
    addMeshSensor(set, "plate", "node", "test plate", rect({-1, y, 1}, {2, 0, 0}, {0, 0, -2}), cell);
    return set;
}

test::SceneBuilder blackGround()
{
    test::SceneBuilder b;
    b.add("ground", rect({-3, 0, 3}, {6, 0, 0}, {0, 0, -6}), b.material("black", glm::vec3(0.0f)));
    b.camera({0, 3, 4}, {0, 0, 0}, {0, 1, 0}, 40.0);
    return b;
}

TEST(Sensors, UnobstructedUnderUniformSky)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // E = pi L from the whole upper hemisphere.
    test::SceneBuilder b = blackGround();
    b.uniformSky(1000.0);
    const SensorSet set = horizontalSensor(1.0f);
    ASSERT_EQ(set.cells.size(), 16u);
    const SensorRun run = renderSensors(*ctx, b.build(), set, 4u << 20);
    expectGridMean(run, set, M_PI * 1000.0, 0.005, "uniform sky, horizontal");
    expectCells(run, std::vector<double>(16, M_PI * 1000.0), "uniform sky, horizontal");
}

TEST(Sensors, UnobstructedUnderCieOvercastSky)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // CIE overcast (type 1, L(theta) = Lz (1 + 2 cos theta) / 3): E = 7 pi Lz / 9 for the sky
    // itself; the renderer's sky is its table (bilinear between nodes: DESIGN.md §1), whose
    // integral is what a sensor must measure and what a daylight factor divides by. The table's
    // integral is within 0.5 % of the closed form (a deterministic check of its resolution).
    test::SceneBuilder b = blackGround();
    const double Lz = 3000.0;
    b.cieSky(1, Lz, 45.0, 180.0);
    const Scene scene = b.build();
    const double tableLux = buildSky(scene)->illuminance(glm::dvec3(0.0, 1.0, 0.0));
    std::printf("[ sensors  ] CIE overcast table: %.6g lux against the closed form's %.6g (%+.3f %%)\n", tableLux,
                7.0 * M_PI * Lz / 9.0, 100.0 * (tableLux / (7.0 * M_PI * Lz / 9.0) - 1.0));
    EXPECT_NEAR(tableLux, 7.0 * M_PI * Lz / 9.0, 0.005 * 7.0 * M_PI * Lz / 9.0);
    const SensorSet set = horizontalSensor(1.0f);
    const SensorRun run = renderSensors(*ctx, scene, set, 4u << 20);
    expectGridMean(run, set, tableLux, 0.005, "CIE overcast, horizontal");
    const auto df = run.r.sensors->jackknife([&](const std::vector<double>& E) {
        double s = 0.0;
        for (double e : E)
            s += e;
        return 100.0 * s / static_cast<double>(E.size()) / tableLux;
    });
    std::printf("[ sensors  ] daylight factor of an unobstructed sensor: %.3f %% +- %.3f\n", df.value, df.stdErr);
    EXPECT_NEAR(df.value, 100.0, kSigmas * df.stdErr);
}

TEST(Sensors, UnobstructedUnderTheSun)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // Horizontal: E = E_n sin h. Vertical, facing south (+z) with the sun at azimuth 150
    // (30 degrees east of south): E = E_n cos h cos 30.
    const double h = 35.0, az = 150.0, En = 80000.0;
    test::SceneBuilder b = blackGround();
    b.sun(h, az, En);
    SensorSet set = horizontalSensor(1.0f);
    addMeshSensor(set, "wall", "node", "test wall", rect({-1, 0.5f, 0.5f}, {2, 0, 0}, {0, 2, 0}), 0.5);
    ASSERT_EQ(set.cells.size(), 32u);
    ASSERT_NEAR(set.cells.back().normal.z, 1.0, 1e-12);
    const SensorRun run = renderSensors(*ctx, b.build(), set, 4u << 20);
    const double rad = M_PI / 180.0;
    std::vector<double> expected(32, En * std::sin(h * rad));
    for (std::size_t c = 16; c < 32; ++c)
        expected[c] = En * std::cos(h * rad) * std::cos((180.0 - az) * rad);
    expectCells(run, expected, "sun, horizontal and vertical");
}

TEST(Sensors, VerticalSensorSeesHalfAUniformSky)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // Nothing below the horizon (a black ground): E = pi L / 2.
    test::SceneBuilder b = blackGround();
    b.uniformSky(1000.0);
    SensorSet set;
    addMeshSensor(set, "wall", "node", "test wall", rect({-1, 0.5f, 0}, {2, 0, 0}, {0, 2, 0}), 0.5);
    const SensorRun run = renderSensors(*ctx, b.build(), set, 4u << 20);
    expectGridMean(run, set, M_PI * 1000.0 / 2.0, 0.005, "uniform sky, vertical");
}

TEST(Sensors, VerticalSensorSeesTheGroundGlow)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // No modelled ground (a speck behind and below the sensors, which face away from it, stands for
    // the geometry), a uniform sky of luminance L
    // and a glowing ground of albedo rho_g: L_g = rho_g E_h / pi = rho_g L, and a vertical sensor
    // sees half of each hemisphere: E = pi L / 2 + pi L_g / 2 = pi L (1 + rho_g) / 2. Facing up,
    // it sees the sky alone: pi L. Every strategy emits the ground's light.
    const double L = 1000.0, rhoG = 0.3;
    test::SceneBuilder b;
    b.add("speck", {{{0, 0, -0.5f}, {0.01f, 0, -0.5f}, {0, 0.01f, -0.5f}}}, b.material("black", glm::vec3(0.0f)));
    b.uniformSky(L);
    b.camera({0, 3, 4}, {0, 0, 0}, {0, 1, 0}, 40.0);
    Scene scene = b.build();
    scene.sky.groundAlbedo = rhoG;
    SensorSet wall;
    addMeshSensor(wall, "wall", "node", "test wall", rect({-1, 0.5f, 0}, {2, 0, 0}, {0, 2, 0}), 0.5);
    const SensorSet up = horizontalSensor(1.0f);
    for (const EmissionMethod m : {EmissionMethod::Uniform, EmissionMethod::Adaptive}) {
        const SensorRun v = renderSensors(*ctx, scene, wall, 4u << 20, m);
        expectGridMean(v, wall, M_PI * L * (1.0 + rhoG) / 2.0, 0.01, cat("ground glow, vertical, ", methodName(m)).c_str());
    }
    const SensorRun h = renderSensors(*ctx, scene, up, 4u << 20);
    expectGridMean(h, up, M_PI * L, 0.01, "ground glow, horizontal facing up");
}

// A black 2 x 2 x 1.2 m room whose ceiling has a 1 x 1 m opening (marked as a portal pane of
// clear "glass" that changes nothing), its floor covered by sensor cells of 0.25 m 1 mm above it.
struct OpeningRoom {
    Scene scene;
    SensorSet set;
    std::vector<double> expected;  // pi L F averaged over each cell
};

// floorAlbedo > 0: a grey floor, for a test that needs an image (the expected values then hold no
// longer: the floor lights the black walls, not the sensors, but the image is not black).
OpeningRoom openingRoom(float floorAlbedo = 0.0f)
{
    test::SceneBuilder b;
    const int black = b.material("black", glm::vec3(0.0f));
    const float S = 2.0f, Hc = 1.2f, o0 = 0.5f, o1 = 1.5f;
    b.add("floor", rect({0, 0, 0}, {S, 0, 0}, {0, 0, S}), b.material("floor", glm::vec3(floorAlbedo)));
    b.add("walls", test::boxWithCeilingOpening(S, Hc, o0, o1), black);
    b.add("opening", rect({o0, Hc, o0}, {o1 - o0, 0, 0}, {0, 0, o1 - o0}), b.glass("clear", glm::vec3(1.0f), 1.0f),
          PortalMark::Panes);
    const double L = 1000.0, y = 0.001;
    b.uniformSky(L);
    b.camera({1.0, 1.0, 1.0}, {1.0, 0.0, 1.0}, {0, 0, -1}, 40.0);
    OpeningRoom room;
    room.scene = b.build();
    addMeshSensor(room.set, "floor", "node", "test floor", rect({0, static_cast<float>(y), S}, {S, 0, 0}, {0, 0, -S}), 0.25);
    for (const SensorCell& c : room.set.cells) {
        // the configuration factor to the opening, averaged over the cell on an 8 x 8 grid
        double F = 0.0;
        for (int i = 0; i < 8; ++i)
            for (int j = 0; j < 8; ++j) {
                const glm::dvec3 p = c.position + glm::dvec3((i + 0.5) / 8.0 - 0.5, 0.0, (j + 0.5) / 8.0 - 0.5) * c.side_m;
                F += test::viewFactorToCeilingRect(p, o0, o1, o0, o1, Hc);
            }
        room.expected.push_back(M_PI * L * F / 64.0);
    }
    return room;
}

class SensorsUnderAnOpening : public ::testing::TestWithParam<std::tuple<EmissionMethod, KernelMode>> {};

TEST_P(SensorsUnderAnOpening, EveryCellMatchesItsConfigurationFactor)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const auto [method, mode] = GetParam();
    const OpeningRoom room = openingRoom();
    ASSERT_EQ(room.set.cells.size(), 64u);
    const SensorRun run = renderSensors(*ctx, room.scene, room.set, 4u << 20, method, mode);
    double sum = 0.0;
    for (double e : room.expected)
        sum += e;
    const std::string what = cat(methodName(method), " ", kernelModeName(mode), ", floor under opening");
    expectGridMean(run, room.set, sum / 64.0, 0.01, what.c_str());
    expectCells(run, room.expected, what.c_str());
}

INSTANTIATE_TEST_SUITE_P(EveryStrategy, SensorsUnderAnOpening,
                         ::testing::Values(std::make_tuple(EmissionMethod::Uniform, KernelMode::Fused),
                                           std::make_tuple(EmissionMethod::Uniform, KernelMode::Wavefront),
                                           std::make_tuple(EmissionMethod::Portal, KernelMode::Fused),
                                           std::make_tuple(EmissionMethod::Adaptive, KernelMode::Fused),
                                           std::make_tuple(EmissionMethod::Adaptive, KernelMode::Wavefront)),
                         [](const auto& info) {
                             return methodName(std::get<0>(info.param)) + "_" + kernelModeName(std::get<1>(info.param));
                         });

TEST(Sensors, AdaptiveEmissionLearnsFromTheSensorsWhenThereIsNoImage)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // With no image, the sensors' crossings feed the adaptive statistics (lib/sensor.h): in the
    // room under an opening, most of the uniform box's paths never enter, and the learned density
    // sends them in. Measured at 2^22 paths: the grid mean's standard error 0.61 lux uniform, 0.25
    // adaptive; required: below 0.7 of uniform's (a 2x efficiency), the same seed for both.
    const OpeningRoom room = openingRoom();
    const SensorRun u = renderSensors(*ctx, room.scene, room.set, 4u << 20, EmissionMethod::Uniform);
    const SensorRun a = renderSensors(*ctx, room.scene, room.set, 4u << 20, EmissionMethod::Adaptive);
    const auto gridMean = [](const std::vector<double>& E) {
        double s = 0.0;
        for (double e : E)
            s += e;
        return s / static_cast<double>(E.size());
    };
    const double seU = u.r.sensors->jackknife(gridMean).stdErr, seA = a.r.sensors->jackknife(gridMean).stdErr;
    std::printf("[ sensors  ] grid mean's standard error: uniform %.3g, adaptive %.3g lux\n", seU, seA);
    EXPECT_LT(seA, 0.7 * seU);
}

TEST(Sensors, TheRelativeTargetSteersBySensorsAndStaysUnbiased)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // --adaptive-target relative with no image: each cell's share of the statistics is scaled by
    // the grid's mean over its own (smoothed) illuminance; every cell still within the chi-square.
    const OpeningRoom room = openingRoom();
    Scene scene = room.scene;
    scene.bounds.grow(sensorBounds(room.set));
    const auto t = test::renderScene(*ctx, scene, 32, 24, 4u << 20, {Roi{0, 0, 32, 24}}, 1, 1024,
                                     [&](RenderSettings& st) {
                                         st.sensors = &room.set;
                                         st.noImage = true;
                                         st.emission.method = EmissionMethod::Adaptive;
                                         st.emission.adaptive.relativeTarget = true;
                                     });
    ASSERT_TRUE(t.result.sensors.has_value());
    SensorRun run{t.result, t.result.sensors->mean(), t.result.sensors->stdErr()};
    double sum = 0.0;
    for (double e : room.expected)
        sum += e;
    expectGridMean(run, room.set, sum / 64.0, 0.01, "adaptive relative, floor under opening");
    expectCells(run, room.expected, "adaptive relative, floor under opening");
}

TEST(Sensors, KernelFormsAddTheSameSums)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // Integer sums of the same segments: bit-identical cells, whichever kernel form ran them.
    const OpeningRoom room = openingRoom();
    const SensorRun f = renderSensors(*ctx, room.scene, room.set, 1u << 18, EmissionMethod::Uniform, KernelMode::Fused);
    const SensorRun w = renderSensors(*ctx, room.scene, room.set, 1u << 18, EmissionMethod::Uniform, KernelMode::Wavefront);
    ASSERT_EQ(f.mean.size(), w.mean.size());
    for (std::size_t c = 0; c < f.mean.size(); ++c)
        EXPECT_EQ(f.mean[c], w.mean[c]) << "cell " << c;
}

TEST(Sensors, SensorAboveAWhiteFloorAgreesWithItsLuminance)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // A white Lambertian floor under a uniform sky: the sensor 1 mm above it measures E, the image
    // the floor's luminance; L = rho E / pi, compared within 4 sigma of both errors together.
    test::SceneBuilder b;
    const double rho = 0.8;
    b.add("floor", rect({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}), b.material("white", glm::vec3(static_cast<float>(rho))));
    b.uniformSky(1000.0);
    b.camera({0, 3, 0}, {0, 0, 0}, {0, 0, -1}, 30.0);
    SensorSet set;
    addMeshSensor(set, "floor", "node", "test floor", rect({-0.5f, 0.001f, 0.5f}, {1, 0, 0}, {0, 0, -1}), 0.25);
    Scene scene = b.build();
    scene.bounds.grow(sensorBounds(set));
    // the image's centre: about the same 1 x 1 m of floor, seen from 3 m with a 30 degree field
    const auto t = test::renderScene(*ctx, scene, 64, 48, 4u << 20, {Roi{24, 16, 40, 32}}, 1, 1024,
                                     [&](RenderSettings& s) { s.sensors = &set; });
    ASSERT_TRUE(t.result.sensors.has_value());
    const auto E = t.result.sensors->jackknife([](const std::vector<double>& v) {
        double sum = 0.0;
        for (double x : v)
            sum += x;
        return sum / static_cast<double>(v.size());
    });
    const double Lc = t.result.roiMean(0), Lcse = t.result.roiMeanStdErr(0);
    const double predicted = rho * E.value / M_PI, predictedSe = rho * E.stdErr / M_PI;
    const double sigma = std::sqrt(predictedSe * predictedSe + Lcse * Lcse);
    std::printf("[ sensors  ] floor luminance %.5g cd/m2 vs rho E / pi = %.5g (E %.5g lux), %+.2f sigma\n", Lc,
                predicted, E.value, (Lc - predicted) / sigma);
    EXPECT_NEAR(Lc, predicted, kSigmas * sigma);
    EXPECT_NEAR(E.value, M_PI * 1000.0, kSigmas * E.stdErr);
}

TEST(Sensors, TheImageIsTheSameWithAndWithoutSensors)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // Sensors block nothing and draw no random numbers: the image is bit-identical.
    for (const KernelMode mode : {KernelMode::Fused, KernelMode::Wavefront}) {
        const OpeningRoom room = openingRoom(0.5f);
        Scene scene = room.scene;
        scene.bounds.grow(sensorBounds(room.set));  // the same emission box for both
        const auto with = test::renderScene(*ctx, scene, 32, 24, 1u << 18, {Roi{0, 0, 32, 24}}, 1, 1024,
                                            [&](RenderSettings& s) {
                                                s.sensors = &room.set;
                                                s.kernels = mode;
                                            });
        const auto without = test::renderScene(*ctx, scene, 32, 24, 1u << 18, {Roi{0, 0, 32, 24}}, 1, 1024,
                                               [&](RenderSettings& s) { s.kernels = mode; });
        ASSERT_TRUE(with.result.sensors.has_value());
        EXPECT_FALSE(without.result.sensors.has_value());
        ASSERT_EQ(with.result.image.rgb.size(), without.result.image.rgb.size());
        std::size_t differ = 0;
        double sum = 0.0;
        for (std::size_t i = 0; i < with.result.image.rgb.size(); ++i) {
            differ += with.result.image.rgb[i] != without.result.image.rgb[i];
            sum += with.result.image.rgb[i];
        }
        EXPECT_EQ(differ, 0u) << kernelModeName(mode);
        EXPECT_GT(sum, 0.0) << "the image must show something for the comparison to mean anything";
    }
}

}  // namespace
}  // namespace fen
