// direct_sun_test.cpp — the annual study's direct-sun pass (host/annual/direct_sun.h,
// kernels/direct_sun.cl; DESIGN.md §8 "The sun apart from the sky") against closed forms and
// against light tracing the sun itself:
//   - unobstructed cells: E_n cos(theta) (1 + cos alpha) / 2 -- the mean direction of a uniform
//     cone of half-angle alpha is its axis times (1 + cos alpha) / 2 -- for cells facing up and east:
//     each value within the disc's spread of cosines, and 2,000 hours' mean within 4 sigma; 0 for a
//     cell facing away and for an hour without sun;
//   - under a horizontal glass pane: E_n cos(theta) T (1 - R(theta)), R the unpolarised Fresnel
//     reflectance, within the disc's spread;
//   - a cell half covered by an opaque sheet 1 mm above it, the sheet's edge its diagonal: on
//     average over 4,000 hours (each its own jitter) half of the unobstructed value, within 4 sigma
//     of the hours' own spread (the disc's penumbra, 9 micrometres wide, is far below that);
//   - in a room with a south and an east glass window: each work-plane cell's direct sun (its mean
//     over 64 copies of the hour, each jittered anew) against the light tracer's estimate of the
//     same thing -- a render of that sun alone, its paths tagged by sky patch, the direct-light
//     matrix's row sum -- within 4 sigma of the two (chi-square p > 1e-4 as well); two unrelated
//     estimators, so this checks the frame, the sun's direction, the cells' squares and the glass
//     together; and the third matrix is all light less the direct;
//   - the same seed gives the same bytes, another seed other values.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <utility>

#include "annual/direct_sun.h"
#include "annual/sky_patches.h"
#include "render/device_scene.h"
#include "sensor/sensor_set.h"
#include "sky/goniogram.h"
#include "support/cl_fixture.h"
#include "support/render_support.h"
#include "support/statistics.h"
#include "support/window_rooms.h"
#include "trace/device_bvh.h"

namespace fen {
namespace {

using test::rect;

// Towards the sky at an altitude and azimuth (degrees; sky/goniogram.h's frame).
glm::dvec3 towards(double altDeg, double aziDeg)
{
    return skyDirection((90.0 - altDeg) * M_PI / 180.0, aziDeg * M_PI / 180.0);
}

// One air/glass interface, unpolarised (kernels/lib/fresnel.h's formula, in double).
double fresnel(double cosI, double eta)
{
    const double ci = std::abs(cosI), ct = std::sqrt(1.0 - (1.0 - ci * ci) / (eta * eta));
    const double rs = (ci - eta * ct) / (ci + eta * ct), rp = (eta * ci - ct) / (eta * ci + ct);
    return 0.5 * (rs * rs + rp * rp);
}

std::vector<float> directSun(ocl::Context& ctx, const Scene& scene, const SensorSet& set,
                             const std::vector<glm::dvec3>& sun, const std::vector<double>& lux, int points,
                             std::uint32_t seed = 1)
{
    const DeviceScene dev(ctx, scene, defaultBvhWidth(false));
    DirectSun pass(ctx, dev, set, sun, lux, points, seed);
    return pass.cells(0, set.cells.size());
}

// Every sample's cosine lies within [cos(theta + alpha), cos(theta - alpha)] of the disc's centre
// at theta: a bound on how far one value (a mean of such samples) may be from the disc's mean.
double discBound(double cosTheta)
{
    const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
    return sinTheta * std::sin(kSunAngularRadiusRad) + (1.0 - std::cos(kSunAngularRadiusRad));
}

// The mean of `values` and its standard error.
std::pair<double, double> meanAndStdErr(const std::vector<float>& values, std::size_t first, std::size_t n)
{
    double sum = 0.0, sq = 0.0;
    for (std::size_t i = first; i < first + n; ++i) {
        sum += values[i];
        sq += static_cast<double>(values[i]) * values[i];
    }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sq / n - mean * mean) / (n - 1))};
}

TEST(DirectSun, UnobstructedCellsSeeTheSunsCosine)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    test::SceneBuilder b;  // a speck far away stands for the scene
    b.add("speck", {{{-30, 0, -30}, {-29.99f, 0, -30}, {-30, 0.01f, -30}}}, b.material("grey", glm::vec3(0.5f)));
    b.camera({0, 3, 4}, {0, 0, 0}, {0, 1, 0}, 40.0);
    const Scene scene = b.build();
    SensorSet set;
    addMeshSensor(set, "up", "node", "plate up", rect({-1, 1, 1}, {2, 0, 0}, {0, 0, -2}), 2.0);
    addMeshSensor(set, "east", "node", "plate east", rect({3, 0, 1}, {0, 0, -2}, {0, 2, 0}), 2.0);
    addMeshSensor(set, "down", "node", "plate down", rect({-1, 5, -1}, {2, 0, 0}, {0, 0, 2}), 2.0);
    ASSERT_EQ(set.cells.size(), 3u);
    std::vector<glm::dvec3> sun = {towards(30, 100), towards(70, 200), towards(10, 90), towards(45, 0)};
    std::vector<double> lux = {80000, 50000, 20000, 0};
    const std::size_t each = sun.size(), repeats = 2000;  // then the first sun again and again
    sun.resize(each + repeats, sun[0]);
    lux.resize(each + repeats, lux[0]);
    const std::vector<float> S = directSun(*ctx, scene, set, sun, lux, 3);
    ASSERT_EQ(S.size(), 3 * sun.size());
    const double disc = 0.5 * (1.0 + std::cos(kSunAngularRadiusRad));
    for (std::size_t c = 0; c < 3; ++c) {
        const char* name = set.sensors[set.cells[c].sensor].name.c_str();
        for (std::size_t h = 0; h < each; ++h) {
            const double cosTheta = glm::dot(set.cells[c].normal, sun[h]);
            const double expected = lux[h] * std::max(0.0, cosTheta) * disc;
            EXPECT_NEAR(S[c * sun.size() + h], expected, lux[h] * discBound(cosTheta) + 1e-3) << name << ", hour " << h;
        }
        // unbiased: the repeats' mean within 4 sigma of the disc's mean
        const auto [mean, se] = meanAndStdErr(S, c * sun.size() + each, repeats);
        const double expected = lux[0] * std::max(0.0, glm::dot(set.cells[c].normal, sun[0])) * disc;
        std::printf("[ sun      ] %s: %.3f lux over %zu hours, %.3f expected, se %.3f\n", name, mean, repeats, expected, se);
        EXPECT_NEAR(mean, expected, 4.0 * se + 1e-9 * expected) << name;
    }
    EXPECT_EQ(S[2 * sun.size() + 0], 0.0f);  // facing down: never
    EXPECT_EQ(S[0 * sun.size() + 3], 0.0f);  // no sun
}

TEST(DirectSun, GlassPassesTTimesOneLessFresnel)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    test::SceneBuilder b;
    b.add("pane", rect({-5, 2, 5}, {10, 0, 0}, {0, 0, -10}), b.glass("glass", glm::vec3(0.85f), 1.5f));
    b.camera({0, 3, 4}, {0, 0, 0}, {0, 1, 0}, 40.0);
    const Scene scene = b.build();
    SensorSet set;
    addMeshSensor(set, "up", "node", "plate up", rect({-0.5f, 0, 0.5f}, {1, 0, 0}, {0, 0, -1}), 1.0);
    const std::vector<glm::dvec3> sun = {towards(90, 0), towards(60, 140), towards(30, 250)};
    const std::vector<double> lux = {100000, 100000, 100000};
    const std::vector<float> S = directSun(*ctx, scene, set, sun, lux, 2);
    const double disc = 0.5 * (1.0 + std::cos(kSunAngularRadiusRad));
    for (std::size_t h = 0; h < sun.size(); ++h) {
        const double expected = lux[h] * sun[h].y * disc * 0.85 * (1.0 - fresnel(sun[h].y, 1.5));
        // the disc's spread of cosines, and of R with them (dR/dtheta < 0.2 here: 1e-3 over the disc)
        EXPECT_NEAR(S[h], expected, lux[h] * (discBound(sun[h].y) + 1e-3)) << "hour " << h;
    }
}

TEST(DirectSun, AShadowEdgeAcrossACellIsAveragedWithoutBias)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // An opaque sheet 1 mm above a 1 m cell (x, z in [0, 1]) covers the half x + z > 1 beyond the
    // diagonal; the sun overhead.
    test::SceneBuilder b;
    b.add("sheet", {{{1, 0.001f, 0}, {1, 0.001f, 5}, {-4, 0.001f, 5}}}, b.material("black", glm::vec3(0.0f)));
    b.camera({0, 3, 4}, {0, 0, 0}, {0, 1, 0}, 40.0);
    const Scene scene = b.build();
    SensorSet set;
    addMeshSensor(set, "cell", "node", "plate", rect({0, 0, 1}, {1, 0, 0}, {0, 0, -1}), 1.0);
    ASSERT_EQ(set.cells.size(), 1u);
    const std::size_t H = 4000;
    const std::vector<glm::dvec3> sun(H, glm::dvec3(0.0, 1.0, 0.0));
    const std::vector<double> lux(H, 1.0);
    const std::vector<float> S = directSun(*ctx, scene, set, sun, lux, 2);
    double sum = 0.0, sq = 0.0;
    for (float v : S) {
        sum += v;
        sq += static_cast<double>(v) * v;
    }
    const double disc = 0.5 * (1.0 + std::cos(kSunAngularRadiusRad));
    const double mean = sum / H, se = std::sqrt((sq / H - mean * mean) / (H - 1));
    std::printf("[ sun      ] half-shadowed cell: %.5f of the sun (0.5 expected), se %.5f\n", mean / disc, se / disc);
    ASSERT_GT(se, 0.0);  // the jitter varies from hour to hour
    EXPECT_NEAR(mean, 0.5 * disc, 4.0 * se);
    // the same seed: the same bytes; another: other values, the same mean
    EXPECT_EQ(directSun(*ctx, scene, set, sun, lux, 2), S);
    const std::vector<float> other = directSun(*ctx, scene, set, sun, lux, 2, 2);
    EXPECT_NE(other, S);
}

TEST(DirectSun, AgreesWithLightTracingTheSunThroughGlassWindows)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // The room with a south and an east window (glass T 0.85): 36 cells of 0.5 m at 0.8 m; the sun
    // at 40 degrees in the south-south-east, 0.533 degrees across, alone (no sky).
    Scene scene = test::windowRoom(test::Windows::Two);
    scene.sky = SkySpec{};
    const double alt = 40.0, azi = 150.0, lux = 30000.0;
    const glm::dvec3 toSun = towards(alt, azi);
    scene.sun.present = true;
    scene.sun.travelDirection = -toSun;
    scene.sun.illuminanceRgb_lux = glm::dvec3(lux);
    scene.sun.angularRadiusRad = kSunAngularRadiusRad;
    SensorSet set;
    addMeshSensor(set, "plane", "node", "work plane", rect({0, 0.8f, 3}, {3, 0, 0}, {0, 0, -3}), 0.5);
    ASSERT_EQ(set.cells.size(), 36u);
    const std::size_t hours = 64;  // the same hour, each with its own jitter: a mean and its spread
    const std::vector<float> S = directSun(*ctx, scene, set, std::vector<glm::dvec3>(hours, toSun),
                                           std::vector<double>(hours, lux), 4);
    // the light tracer: every path tagged by its patch (all of them the sun's), the direct matrix's rows
    const int mf = 1;
    const std::size_t P = skyPatchCount(mf), cells = set.cells.size();
    scene.bounds.grow(sensorBounds(set));
    const auto t = test::renderScene(*ctx, scene, 8, 8, 16u << 20, {Roi{0, 0, 8, 8}}, 3, 1024, [&](RenderSettings& s) {
        s.sensors = &set;
        s.noImage = true;
        s.emission.method = EmissionMethod::Adaptive;
        s.skyPatchMF = mf;
    });
    ASSERT_TRUE(t.result.daylightCoefficients);
    EXPECT_EQ(t.result.counts.badContributions, 0u);
    const std::vector<double> D = t.result.daylightCoefficients->mean(), se = t.result.daylightCoefficients->stdErr();
    ASSERT_EQ(D.size(), 3 * cells * P);
    double chi2 = 0.0, worst = 0.0, lit = 0.0, traced = 0.0;
    int k = 0, shaded = 0;
    for (std::size_t c = 0; c < cells; ++c) {
        double d = 0.0, var = 0.0;
        for (std::size_t p = 0; p < P; ++p) {
            d += D[(cells + c) * P + p];
            var += se[(cells + c) * P + p] * se[(cells + c) * P + p];  // one patch holds it all
            // all light less direct is what the third matrix holds
            ASSERT_NEAR(D[(2 * cells + c) * P + p], D[c * P + p] - D[(cells + c) * P + p], 1e-9 * D[c * P + p] + 1e-300);
        }
        const auto [pass, passSe] = meanAndStdErr(S, c * hours, hours);
        if (pass == 0.0) {
            EXPECT_EQ(d, 0.0) << "cell " << c << ": in shadow for the pass, lit for the tracer";
            ++shaded;
            continue;
        }
        const double z = (pass - d) / std::sqrt(var + passSe * passSe);
        chi2 += z * z * 13.0 / 15.0;  // the tracer's 16 batches (the pass's 64 hours: closer to normal)
        worst = std::max(worst, std::abs(z));
        ++k;
        lit += pass;
        traced += d;
        EXPECT_LE(std::abs(z), 4.0) << "cell " << c << ": pass " << pass << " lux (se " << passSe << "), light tracer " << d
                                    << " (se " << std::sqrt(var) << ")";
    }
    const double pv = test::gammaQ(0.5 * k, 0.5 * chi2);
    std::printf("[ sun      ] %d lit cells (%d in shadow): pass %.6g lux, light tracer %.6g (%+.3f %%), chi2 %.1f, p %.3g, "
                "worst %.2f sigma\n", k, shaded, lit / k, traced / k, 100.0 * (lit / traced - 1.0), chi2, pv, worst);
    EXPECT_GT(k, 6);
    EXPECT_GT(shaded, 6);
    EXPECT_GT(pv, 1e-4);
}

}  // namespace
}  // namespace fen
