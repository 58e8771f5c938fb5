// ground_test.cpp — the ground's glow below the horizon (DESIGN.md §1 "Sky") in whole renders,
// against closed forms, under every emission strategy. As in analytic_test.cpp, each compares the
// mean luminance of a region with its exact value within 4 standard errors of that mean (the
// standard error from the spread of the 16 independent batches; fixed seeds, shifted by
// FEN_TEST_SEED), requires that error to be small enough for the comparison to mean something,
// and prints the deviation in sigmas. The camera pass is checked exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "io/image.h"
#include "support/cl_fixture.h"
#include "support/render_support.h"

namespace fen {
namespace {

using test::rect;

constexpr double kSigmas = 4.0;

void expectClean(const RenderResult& r)
{
    EXPECT_EQ(r.counts.badContributions, 0u);
    EXPECT_EQ(r.counts.overflows, 0u);
    for (float v : r.image.rgb)
        ASSERT_TRUE(std::isfinite(v));
}

void expectMean(const RenderResult& r, std::size_t roi, double expected, double maxRelSe, const char* what)
{
    const double m = r.roiMean(roi), se = r.roiMeanStdErr(roi);
    std::printf("[ ground   ] %s: measured %.6g, expected %.6g, se %.3g (%.2f%%), %+.2f sigma\n", what, m, expected,
                se, 100.0 * se / expected, (m - expected) / se);
    EXPECT_NEAR(m, expected, kSigmas * se) << what << ": " << m << " vs " << expected << " (se " << se << ", "
                                           << (m - expected) / se << " sigma)";
    EXPECT_LE(se, maxRelSe * expected) << what << ": too noisy to test";
}

constexpr double kSkyL = 1000.0;

// A 2 x 2 m Lambertian plate (albedo rhoP) at height 1 m, alone under a uniform sky of luminance
// kSkyL with a ground of albedo rhoG (and the sun when sunLux > 0), seen from 3 m below: its
// underside sees nothing but the ground's glow, so it receives E_down = pi L_g and shows rhoP L_g.
Scene downFacingPlate(double rhoP, double rhoG, double sunLux = 0.0)
{
    test::SceneBuilder b;
    b.add("plate", rect({-1, 1, -1}, {2, 0, 0}, {0, 0, 2}), b.material("m", glm::vec3(float(rhoP))));
    b.uniformSky(kSkyL);
    if (sunLux > 0.0)
        b.sun(40.0, 200.0, sunLux);
    b.camera({0, -2, 0}, {0, 1, 0}, {0, 0, -1}, 30.0);
    Scene s = b.build();
    s.sky.groundAlbedo = rhoG;
    return s;
}

// The central half of the image.
Roi centre(int w, int h) { return Roi{w / 4, h / 4, 3 * w / 4, 3 * h / 4}; }

void plateUnder(EmissionMethod method, double sunLux, std::uint64_t paths, const char* what)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const double rhoP = 0.7, rhoG = 0.4;
    const int W = 64, H = 48;
    const auto t = test::renderScene(*ctx, downFacingPlate(rhoP, rhoG, sunLux), W, H, paths, {centre(W, H)}, 3, 1024,
                                     [&](RenderSettings& s) { s.emission.method = method; });
    expectClean(t.result);
    ASSERT_TRUE(t.sky && t.sky->hasGround());
    // L_g = rho_g E_h / pi, E_h = pi L + E sin h: the closed form, and the table's own value.
    const double Lg = rhoG * (M_PI * kSkyL + sunLux * std::sin(40.0 * M_PI / 180.0)) / M_PI;
    EXPECT_NEAR(t.sky->groundLuminance(), Lg, 1e-9 * Lg);
    expectMean(t.result, 0, rhoP * Lg, 0.01, what);
}

TEST(GroundGlow, DownFacingPlateSeesTheGroundUniform)
{
    plateUnder(EmissionMethod::Uniform, 0.0, 1u << 20, "down-facing plate, uniform");
}

TEST(GroundGlow, DownFacingPlateSeesTheGroundAdaptive)
{
    plateUnder(EmissionMethod::Adaptive, 0.0, 1u << 20, "down-facing plate, adaptive");
}

TEST(GroundGlow, TheSunLightsTheGroundToo)
{
    // E_h = pi L + E sin(40 deg): the sun's share of the ground's glow.
    plateUnder(EmissionMethod::Uniform, 20000.0, 1u << 20, "down-facing plate, sun and sky, uniform");
}

// A closed black 2 x 2 x 1.2 m box whose floor has a 1 x 1 m opening, marked as a portal (a fully
// transparent pane), under a uniform sky with a ground of albedo rhoG. Its white ceiling (albedo
// rhoP) faces the opening: a ceiling point receives pi L_g F, F its configuration factor to the
// opening, so it shows rhoP L_g F. No sky light reaches the ceiling's underside: the light that
// enters the box comes from the ground, upwards -- the portal strategies' light.
constexpr float kBox = 2.0f, kBoxH = 1.2f, kOpen0 = 0.5f, kOpen1 = 1.5f;

Scene boxOverAFloorOpening(double rhoP, double rhoG)
{
    test::SceneBuilder b;
    const int black = b.material("black", glm::vec3(0.0f));
    const float S = kBox, Hc = kBoxH, o0 = kOpen0, o1 = kOpen1;
    std::vector<Triangle> shell;
    for (const auto& r : {rect({0, 0, 0}, {S, 0, 0}, {0, Hc, 0}), rect({0, 0, S}, {S, 0, 0}, {0, Hc, 0}),
                          rect({0, 0, 0}, {0, 0, S}, {0, Hc, 0}), rect({S, 0, 0}, {0, 0, S}, {0, Hc, 0}),
                          // the floor around the opening
                          rect({0, 0, 0}, {S, 0, 0}, {0, 0, o0}), rect({0, 0, o1}, {S, 0, 0}, {0, 0, S - o1}),
                          rect({0, 0, o0}, {o0, 0, 0}, {0, 0, o1 - o0}),
                          rect({o1, 0, o0}, {S - o1, 0, 0}, {0, 0, o1 - o0})})
        shell.insert(shell.end(), r.begin(), r.end());
    b.add("shell", shell, black);
    b.add("ceiling", rect({0, Hc, 0}, {S, 0, 0}, {0, 0, S}), b.material("white", glm::vec3(float(rhoP))));
    b.add("opening", rect({o0, 0, o0}, {o1 - o0, 0, 0}, {0, 0, o1 - o0}), b.glass("open", glm::vec3(1.0f), 1.0f),
          PortalMark::Panes);
    b.uniformSky(kSkyL);
    b.camera({1.0, 0.2, 1.0}, {1.0, 1.2, 1.0}, {0, 0, -1}, 60.0);
    Scene s = b.build();
    s.sky.groundAlbedo = rhoG;
    return s;
}

void ceilingOverOpening(const std::function<void(RenderSettings&)>& emission, std::uint64_t paths, const char* what)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const double rhoP = 0.8, rhoG = 0.5;
    const int W = 48, H = 36;
    const Roi roi{12, 9, 36, 27};
    const Scene scene = boxOverAFloorOpening(rhoP, rhoG);
    const auto t = test::renderScene(*ctx, scene, W, H, paths, {roi}, 5, 1024, emission);
    expectClean(t.result);
    ASSERT_TRUE(t.sky && t.sky->hasGround());
    const double Lg = t.sky->groundLuminance();
    EXPECT_NEAR(Lg, rhoG * kSkyL, 1e-9 * Lg);
    // Per pixel: the ceiling point it sees; its factor to the opening 1.2 m below is the one of the
    // mirror image (a floor point under a ceiling opening), Siegel & Howell's formula.
    double sum = 0.0;
    for (int y = roi.y0; y < roi.y1; ++y)
        for (int x = roi.x0; x < roi.x1; ++x) {
            const glm::dvec3 p = test::pixelOnPlaneY(scene.cameras[0], W, H, x + 0.5, y + 0.5, kBoxH);
            ASSERT_TRUE(p.x > 0.0 && p.x < kBox && p.z > 0.0 && p.z < kBox);
            sum += rhoP * Lg * test::viewFactorToCeilingRect({p.x, 0.0, p.z}, kOpen0, kOpen1, kOpen0, kOpen1, kBoxH);
        }
    expectMean(t.result, 0, sum / roi.pixels(), 0.015, what);
}

TEST(GroundGlow, CeilingOverAFloorOpeningPortal)
{
    ceilingOverOpening([](RenderSettings& s) { s.emission.method = EmissionMethod::Portal; }, 1u << 20,
                       "ceiling over a floor opening, portal");
}

TEST(GroundGlow, CeilingOverAFloorOpeningAdaptiveOverPortals)
{
    ceilingOverOpening(
        [](RenderSettings& s) {
            s.emission.method = EmissionMethod::Adaptive;
            s.emission.adaptive.base = EmissionMethod::Portal;
        },
        1u << 20, "ceiling over a floor opening, adaptive over portals");
}

TEST(GroundGlow, CeilingOverAFloorOpeningAdaptive)
{
    ceilingOverOpening([](RenderSettings& s) { s.emission.method = EmissionMethod::Adaptive; }, 2u << 20,
                       "ceiling over a floor opening, adaptive");
}

TEST(GroundGlow, TheCameraSeesTheGroundBelowTheHorizon)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // Nothing in view (one small plate far overhead, behind the camera): what a pixel shows is what
    // the camera pass finds where its rays escape -- the sky above the horizon, L_g below it --
    // exactly, up to the float table and the film's fixed point.
    for (double rhoG : {0.3, 0.0})
        for (const bool down : {true, false}) {
            SCOPED_TRACE(testing::Message() << "ground albedo " << rhoG << (down ? ", looking down" : ", level"));
            test::SceneBuilder b;
            b.add("far", rect({-0.5f, 100, -0.5f}, {1, 0, 0}, {0, 0, 1}), b.material("m", glm::vec3(0.5f)));
            b.uniformSky(2000.0);
            if (down)
                b.camera({0, 0, 0}, {0, -1, 0}, {0, 0, -1}, 60.0);
            else
                b.camera({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 60.0);
            Scene scene = b.build();
            scene.sky.groundAlbedo = rhoG;
            const int W = 32, H = 32;
            const auto t = test::renderScene(*ctx, scene, W, H, 1u << 16, {}, 1, 1024,
                                             [](RenderSettings& s) { s.cameraSpp = 4; });
            expectClean(t.result);
            const double Lg = rhoG > 0.0 ? t.sky->groundLuminance() : 0.0;
            EXPECT_NEAR(Lg, rhoG * 2000.0, 1e-9 * 2000.0);
            const CameraSpec& cam = scene.cameras[0];
            const double tanY = std::tan(cam.yfovRad / 2), tanX = tanY;
            auto dirY = [&](double px, double py) {
                return glm::normalize(cam.forward + (2.0 * px / W - 1) * tanX * cam.right +
                                      (1.0 - 2.0 * py / H) * tanY * cam.up).y;
            };
            int sky = 0, ground = 0;
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    // the pixel's whole square above or below the horizon (its corners)
                    double lo = 1.0, hi = -1.0;
                    for (int a = 0; a < 2; ++a)
                        for (int c = 0; c < 2; ++c) {
                            lo = std::min(lo, dirY(x + a, y + c));
                            hi = std::max(hi, dirY(x + a, y + c));
                        }
                    const double Lm = t.result.image.luminance(std::size_t(y) * W + x);
                    if (lo > 0.0) {
                        EXPECT_NEAR(Lm, 2000.0, 2000.0 * 1e-6) << x << "," << y;
                        ++sky;
                    } else if (hi < 0.0) {
                        EXPECT_NEAR(Lm, Lg, 2000.0 * 1e-6) << x << "," << y;
                        ++ground;
                    }
                }
            EXPECT_GT(ground, down ? W * H - 1 : 400);
            if (!down) {
                EXPECT_GT(sky, 400);
            }
        }
}

}  // namespace
}  // namespace fen
