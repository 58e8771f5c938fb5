// analytic_test.cpp — whole renders against closed forms (DESIGN.md §2's normalisation checks and
// more). Each compares the mean luminance of a region with its exact value within 4 standard
// errors of that mean, the standard error measured from the 16 independent batches; each also
// requires that error to be small enough for the comparison to mean something, and the NaN and
// overflow counters to be zero.
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

double Y(glm::vec3 c) { return luminance(c.r, c.g, c.b); }

void expectClean(const RenderResult& r)
{
    EXPECT_EQ(r.counts.badContributions, 0u);
    EXPECT_EQ(r.counts.overflows, 0u);
    for (float v : r.image.rgb)
        ASSERT_TRUE(std::isfinite(v));
}

// |measured - expected| <= 4 se, and se <= maxRelSe * expected.
void expectMean(const RenderResult& r, std::size_t roi, double expected, double maxRelSe,
                const char* what)
{
    const double m = r.roiMean(roi), se = r.roiMeanStdErr(roi);
    std::printf("[ analytic ] %s: measured %.6g, expected %.6g, se %.3g (%.2f%%), %+.2f sigma\n", what,
                m, expected, se, 100.0 * se / expected, (m - expected) / se);
    EXPECT_NEAR(m, expected, kSigmas * se) << what << ": " << m << " vs " << expected << " (se " << se
                                          << ", " << (m - expected) / se << " sigma)";
    EXPECT_LE(se, maxRelSe * expected) << what << ": too noisy to test";
}

// The central half of the image.
Roi centre(int w, int h) { return Roi{w / 4, h / 4, 3 * w / 4, 3 * h / 4}; }

TEST(Analytic, LambertianPlaneUnderTheSun)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // L = rho E sin(h) / pi everywhere on the plane.
    test::SceneBuilder b;
    const glm::vec3 rho(0.5f, 0.4f, 0.3f);
    b.add("plane", rect({-1, 0, -1}, {2, 0, 0}, {0, 0, 2}), b.material("m", rho));
    const double h = 40.0, E = 10000.0;
    b.sun(h, 200.0, E);
    b.camera({0, 3, 0}, {0, 0, 0}, {0, 0, -1}, 30.0);
    const int W = 64, H = 48;
    const auto t = test::renderScene(*ctx, b.build(), W, H, 4u << 20, {centre(W, H)});
    expectClean(t.result);
    expectMean(t.result, 0, Y(rho) * E * std::sin(h * M_PI / 180) / M_PI, 0.005, "sun on plane");
}

TEST(Analytic, LambertianPlaneUnderASunDisk)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // A sun of angular radius 10 deg (the largest allowed) still gives the plane its normal
    // illuminance times sin(h): directions spread over the disk, not the illuminance.
    test::SceneBuilder b;
    const glm::vec3 rho(0.5f);
    b.add("plane", rect({-1, 0, -1}, {2, 0, 0}, {0, 0, 2}), b.material("m", rho));
    const double h = 50.0, E = 10000.0;
    b.sun(h, 120.0, E, 10.0);
    b.camera({0, 3, 0}, {0, 0, 0}, {0, 0, -1}, 30.0);
    const int W = 64, H = 48;
    const auto t = test::renderScene(*ctx, b.build(), W, H, 4u << 20, {centre(W, H)});
    expectClean(t.result);
    expectMean(t.result, 0, 0.5 * E * std::sin(h * M_PI / 180) / M_PI, 0.005, "sun disk on plane");
}

TEST(Analytic, LambertianPlaneUnderUniformSky)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // L = rho L_sky: a plane sees the whole sky hemisphere.
    test::SceneBuilder b;
    const glm::vec3 rho(0.7f);
    b.add("plane", rect({-1, 0, -1}, {2, 0, 0}, {0, 0, 2}), b.material("m", rho));
    b.uniformSky(1000.0);
    b.camera({0, 3, 0}, {0, 0, 0}, {0, 0, -1}, 30.0);
    const int W = 64, H = 48;
    const auto t = test::renderScene(*ctx, b.build(), W, H, 4u << 20, {centre(W, H)});
    expectClean(t.result);
    expectMean(t.result, 0, 0.7 * 1000.0, 0.005, "uniform sky on plane");
}

TEST(Analytic, LambertianPlaneUnderCieClearSkyAndSun)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // Sun and a CIE standard clear sky together: L = rho (E_sun sin h + E_sky) / pi, E_sky the
    // horizontal illuminance of the sky (an independent quadrature of the goniogram).
    test::SceneBuilder b;
    const glm::vec3 rho(0.5f);
    b.add("plane", rect({-1, 0, -1}, {2, 0, 0}, {0, 0, 2}), b.material("m", rho));
    const double h = 30.0, E = 60000.0;
    b.sun(h, 135.0, E);
    b.cieSky(12, 4000.0, h, 135.0);
    b.camera({0, 3, 0}, {0, 0, 0}, {0, 0, -1}, 30.0);
    const int W = 64, H = 48;
    const auto t = test::renderScene(*ctx, b.build(), W, H, 4u << 20, {centre(W, H)});
    expectClean(t.result);
    const double Esky = t.sky->illuminance(glm::dvec3(0, 1, 0));
    expectMean(t.result, 0, 0.5 * (E * std::sin(h * M_PI / 180) + Esky) / M_PI, 0.005,
               "sun + CIE sky on plane");
}

TEST(Analytic, VerticalPlateSeesHalfAUniformSky)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // Nothing below the horizon: a vertical plate receives pi L / 2, so L_plate = rho L / 2.
    test::SceneBuilder b;
    b.add("plate", rect({-1, 0, 0}, {2, 0, 0}, {0, 2, 0}), b.material("m", glm::vec3(0.6f)));
    b.uniformSky(2000.0);
    b.camera({0, 1, 4}, {0, 1, 0}, {0, 1, 0}, 20.0);
    const int W = 64, H = 48;
    const auto t = test::renderScene(*ctx, b.build(), W, H, 4u << 20, {centre(W, H)});
    expectClean(t.result);
    expectMean(t.result, 0, 0.6 * 2000.0 / 2.0, 0.005, "vertical plate");
}

TEST(Analytic, SunOnAWallLightsOnlyItsSunnySide)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // A vertical plate facing south and north; sun due south at altitude 30: the south face has
    // L = rho E cos(30) / pi, the north face nothing at all (two-sided surfaces, no leaks).
    test::SceneBuilder b;
    b.add("plate", rect({-1, 0, 0}, {2, 0, 0}, {0, 2, 0}), b.material("m", glm::vec3(0.5f)));
    b.sun(30.0, 180.0, 20000.0);
    b.camera({0, 1, 4}, {0, 1, 0}, {0, 1, 0}, 20.0, "south");
    const int W = 64, H = 48;
    Scene s = b.build();
    const auto south = test::renderScene(*ctx, s, W, H, 2u << 20, {centre(W, H)});
    expectClean(south.result);
    expectMean(south.result, 0, 0.5 * 20000.0 * std::cos(M_PI / 6) / M_PI, 0.005, "sunny face");
    s.cameras[0].position = glm::dvec3(0, 1, -4);
    s.cameras[0].forward = glm::dvec3(0, 0, 1);
    s.cameras[0].right = glm::dvec3(-1, 0, 0);
    const auto north = test::renderScene(*ctx, s, W, H, 2u << 20, {centre(W, H)});
    EXPECT_EQ(north.result.roiMean(0), 0.0) << "light leaked to the shaded face";
}

TEST(Analytic, FloorUnderAnOpeningInABlackRoom)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // Uniform sky seen through a 1 x 1 m opening in the ceiling of a black 2 x 2 x 1.2 m room:
    // a floor point receives pi L F, F its configuration factor to the opening, so its
    // luminance is rho L F (Siegel & Howell's parallel-rectangle formula), per pixel.
    test::SceneBuilder b;
    const int black = b.material("black", glm::vec3(0.0f));
    const float S = 2.0f, Hc = 1.2f, o0 = 0.5f, o1 = 1.5f;
    b.add("floor", rect({0, 0, 0}, {S, 0, 0}, {0, 0, S}), b.material("floor", glm::vec3(0.8f)));
    b.add("walls", test::boxWithCeilingOpening(S, Hc, o0, o1), black);
    b.uniformSky(1000.0);
    b.camera({1.0, 1.0, 1.0}, {1.0, 0.0, 1.0}, {0, 0, -1}, 40.0);
    const int W = 48, H = 36;
    const Roi roi{16, 12, 32, 24};
    const Scene scene = b.build();
    const auto t = test::renderScene(*ctx, scene, W, H, 24u << 20, {roi});
    expectClean(t.result);
    const double expected = test::floorUnderOpeningMean(scene.cameras[0], W, H, roi, 0.8, 1000.0, Hc, o0, o1);
    expectMean(t.result, 0, expected, 0.01, "floor under opening");
}

TEST(Analytic, SunThroughAGlassPaneLandsWhereGeometrySays)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // Black 4 x 4 x 2 m room, a 1 x 1 m glass pane in the ceiling, the sun due south at 60 deg:
    // the patch on the floor is the pane moved 2 / tan(60) = 1.155 m north, with luminance
    // rho E sin(60) / pi * T (1 - R(30 deg)); outside it the floor is exactly black.
    test::SceneBuilder b;
    const int black = b.material("black", glm::vec3(0.0f));
    const float S = 4.0f, Hc = 2.0f;
    const float px0 = 1.5f, px1 = 2.5f, pz0 = 2.5f, pz1 = 3.5f;
    b.add("floor", rect({0, 0, 0}, {S, 0, 0}, {0, 0, S}), b.material("floor", glm::vec3(0.5f)));
    b.add("shell", test::boxWithCeilingOpening(S, Hc, px0, px1, pz0, pz1), black);
    const glm::vec3 T(0.9f);
    b.add("pane", rect({px0, Hc, pz0}, {px1 - px0, 0, 0}, {0, 0, pz1 - pz0}), b.glass("glass", T, 1.5f));
    const double E = 50000.0, h = 60.0;
    b.sun(h, 180.0, E);
    const double shift = Hc / std::tan(h * M_PI / 180);
    b.camera({2.0, 1.0, 1.8}, {2.0, 0.0, 1.8}, {0, 0, -1}, 70.0);
    const int W = 64, H = 64;
    const Scene scene = b.build();
    // Regions: pixels whose floor points are >= 4 cm inside the patch, and >= 4 cm outside it.
    const CameraSpec& cam = scene.cameras[0];
    auto floorAt = [&](int x, int y) { return test::pixelOnPlaneY(cam, W, H, x + 0.5, y + 0.5, 0.0); };
    const double z0 = pz0 - shift, z1 = pz1 - shift;
    Roi inside{W, H, 0, 0}, outside{0, 0, W, 4};
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const glm::dvec3 p = floorAt(x, y);
            if (p.x > px0 + 0.04 && p.x < px1 - 0.04 && p.z > z0 + 0.04 && p.z < z1 - 0.04) {
                inside.x0 = std::min(inside.x0, x);
                inside.y0 = std::min(inside.y0, y);
                inside.x1 = std::max(inside.x1, x + 1);
                inside.y1 = std::max(inside.y1, y + 1);
            }
        }
    // Shrink to a rectangle fully inside (the patch is a rectangle in the image up to perspective).
    inside = Roi{inside.x0 + 1, inside.y0 + 1, inside.x1 - 1, inside.y1 - 1};
    for (int y = inside.y0; y < inside.y1; ++y)
        for (int x = inside.x0; x < inside.x1; ++x) {
            const glm::dvec3 p = floorAt(x, y);
            ASSERT_TRUE(p.x > px0 && p.x < px1 && p.z > z0 && p.z < z1);
        }
    for (int y = outside.y0; y < outside.y1; ++y)
        for (int x = outside.x0; x < outside.x1; ++x) {
            const glm::dvec3 p = floorAt(x, y);
            ASSERT_TRUE(p.z < z0 - 0.04 || p.z > z1 + 0.04 || p.x < px0 - 0.04 || p.x > px1 + 0.04);
        }
    const auto t = test::renderScene(*ctx, scene, W, H, 4u << 20, {inside, outside});
    expectClean(t.result);
    const double ci = std::sin(h * M_PI / 180);  // cosine to the pane's (vertical) normal
    const double ct = std::sqrt(1 - (1 - ci * ci) / 2.25);
    const double rs = (ci - 1.5 * ct) / (ci + 1.5 * ct), rp = (1.5 * ci - ct) / (1.5 * ci + ct);
    const double R = 0.5 * (rs * rs + rp * rp);
    expectMean(t.result, 0, 0.5 * E * std::sin(h * M_PI / 180) / M_PI * 0.9 * (1 - R), 0.01,
               "sun patch through glass");
    EXPECT_EQ(t.result.roiMean(1), 0.0) << "light outside the geometric sun patch";
}

// The integrating sphere below, rendered with `paths` paths and settings changed by `tweak`.
RenderResult integratingSphere(ocl::Context& ctx, std::uint64_t paths,
                               const std::function<void(RenderSettings&)>& tweak, const char* what)
{
    // A white sphere (albedo 0.8) with a polar cap of half-angle 30 deg removed, under a uniform
    // sky: every wall point has the same luminance, rho L f / (1 - rho (1 - f)) with f the cap's
    // share of the sphere, (1 - cos 30)/2 -- the integrating-sphere result, which holds because a
    // sphere's points all exchange light in proportion to area. Paths bounce ~4 times on average.
    test::SceneBuilder b;
    const double rho = 0.8, alpha = 30.0 * M_PI / 180.0;
    const int rings = 180, segs = 360;
    std::vector<Triangle> tris;
    auto at = [&](int r, int s) -> glm::vec3 {
        const double th = M_PI * r / rings, ph = 2.0 * M_PI * (s % segs) / segs;
        return glm::vec3(glm::dvec3(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph)));
    };
    const int capRings = static_cast<int>(std::lround(alpha / M_PI * rings));
    for (int r = capRings; r < rings; ++r)
        for (int s = 0; s < segs; ++s) {
            const glm::vec3 a = at(r, s), bb = at(r, s + 1), c = at(r + 1, s + 1), d = at(r + 1, s);
            tris.push_back({a, bb, d});
            if (r != rings - 1)
                tris.push_back({bb, c, d});
        }
    b.add("sphere", tris, b.material("white", glm::vec3(float(rho))));
    b.uniformSky(1000.0);
    b.camera({0, 0, 0}, {0, -1, 0}, {0, 0, -1}, 60.0);
    const int W = 32, H = 32;
    const auto t = test::renderScene(ctx, b.build(), W, H, paths, {Roi{0, 0, W, H}}, 1, 200, tweak);
    expectClean(t.result);
    // f from the tessellation's own cap: rings are at exact multiples of 180/rings degrees.
    const double capAngle = M_PI * capRings / rings;
    const double f = (1.0 - std::cos(capAngle)) / 2.0;
    expectMean(t.result, 0, rho * 1000.0 * f / (1.0 - rho * (1.0 - f)), 0.01, what);
    return t.result;
}

TEST(Analytic, IntegratingSphereConservesEnergyOverManyBounces)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    integratingSphere(*ctx, 8u << 20, {}, "integrating sphere");
}

TEST(Analytic, SplitPathsConserveEnergy)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // Every path splits at its first hit into 4 branches of a quarter of its weight (a weight unit
    // far below any path's): the branches' sum must carry exactly the light one path would.
    integratingSphere(*ctx, 2u << 20, [](RenderSettings& s) {
        s.splitMax = 4;
        s.splitWeight = 1e-6;
    }, "integrating sphere, split paths");
}

// Adaptive emission with the guide, its tables learned on the passes, used wherever a slot has
// seen anything (the weights at work): at a path's first diffuse vertex, or at every one.
std::function<void(RenderSettings&)> guided(bool everyVertex)
{
    return [everyVertex](RenderSettings& s) {
        s.emission.method = EmissionMethod::Adaptive;
        s.emission.adaptive.firstPass = 1u << 16;
        s.emission.adaptive.guide.enabled = true;
        s.emission.adaptive.guide.everyVertex = everyVertex;
        s.emission.adaptive.guide.minConnections = 8.0;
        s.emission.adaptive.guide.minGain = 1.0;
    };
}

TEST(Analytic, GuidedFirstBounceConservesEnergy)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // The camera sees the lower part of the sphere, so the tables are far from uniform, and every
    // path's weight is divided by the density of the leaf it left through. The mean must not move.
    // The counters: with no splitting a path is guided at most once, at its first diffuse vertex
    // (most emitted paths land on the sphere's outside, where nothing is learned; the light inside
    // escapes only through the cap, so those paths make several diffuse vertices).
    const auto r = integratingSphere(*ctx, 4u << 20, guided(false), "integrating sphere, guided first bounce");
    EXPECT_GT(r.counts.guidedVertices, r.paths / 10);
    EXPECT_LE(r.counts.guidedVertices, r.paths);
    EXPECT_GT(r.counts.diffuseVertices, r.paths);
}

TEST(Analytic, GuidedEveryVertexConservesEnergy)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // The guide drawing at every diffuse vertex whose slot is learned: a path's weight is divided
    // by a density at each of its bounces, the tables learned at first vertices only. The mean must
    // not move, and far more vertices than paths must have been guided (at most one a path above).
    const auto r = integratingSphere(*ctx, 4u << 20, guided(true), "integrating sphere, guided at every vertex");
    EXPECT_GT(r.counts.guidedVertices, 2 * r.paths);
    EXPECT_LE(r.counts.guidedVertices, r.counts.diffuseVertices);
}

TEST(Analytic, WeightWindowsConserveEnergy)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // Weight windows at the first diffuse vertex, learned with the guide, by either rule: paths
    // whose expected contribution (or its root second moment) is far above the target split, those
    // far below are culled (surviving with at least 1/4, their weight over the odds). Both must
    // happen, and the mean must not move.
    for (const auto rule : {GuideOptions::WindowRule::Mean, GuideOptions::WindowRule::Moment}) {
        const bool moment = rule == GuideOptions::WindowRule::Moment;
        const auto r = integratingSphere(*ctx, 4u << 20, [rule](RenderSettings& s) {
            guided(false)(s);
            s.emission.adaptive.guide.window = true;
            s.emission.adaptive.guide.windowRule = rule;
            s.emission.adaptive.guide.windowMinVisits = 16.0;
            s.emission.adaptive.guide.windowMinSurvival = 0.25;
        }, moment ? "integrating sphere, weight windows (moment)" : "integrating sphere, weight windows (mean)");
        EXPECT_GT(r.counts.splitBranches, r.paths / 100) << moment;
        EXPECT_GT(r.counts.windowCulls, r.paths / 100) << moment;
        EXPECT_GT(r.emission["guide"].value("window_slots", 0), 0) << moment;
    }
}

TEST(Analytic, WeightWindowsPastTheFirstVertexConserveEnergy)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // Windows that only split (as by default), at a path's first diffuse vertex alone, then also at
    // its later ones with the first vertex's windows (--adaptive-window-later 1), then with windows
    // four times lower there (the default): a path not split at its first vertex splits at the
    // first later one where its ratio to the slot's window, times that factor, is 2 or more, its
    // branches scattering as later vertices do. Every mean must hold, and each step must split
    // more than the one before it, from the same seed.
    struct Case {
        bool every;
        double later;
        const char* name;
    };
    const Case cases[] = {{false, 4.0, "integrating sphere, windows at the first vertex"},
                          {true, 1.0, "integrating sphere, the first vertex's windows at every vertex"},
                          {true, 4.0, "integrating sphere, windows 4x lower past the first vertex"}};
    std::uint64_t branches[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k) {
        const Case c = cases[k];
        const auto r = integratingSphere(*ctx, 4u << 20, [c](RenderSettings& s) {
            guided(false)(s);
            s.emission.adaptive.guide.window = true;
            s.emission.adaptive.guide.windowMinVisits = 16.0;
            s.emission.adaptive.guide.windowEveryVertex = c.every;
            s.emission.adaptive.guide.windowLater = c.later;
        }, c.name);
        EXPECT_EQ(r.counts.windowCulls, 0u) << c.name;
        EXPECT_EQ(r.emission["guide"].value("window_vertices", ""), c.every ? "every" : "first");
        EXPECT_EQ(r.emission["guide"].value("window_later", -1.0), c.every ? c.later : 0.0);
        branches[k] = r.counts.splitBranches;
    }
    std::printf("[ windows ] split branches: first vertex %llu, every vertex %llu, 4x lower past it %llu\n",
                static_cast<unsigned long long>(branches[0]), static_cast<unsigned long long>(branches[1]),
                static_cast<unsigned long long>(branches[2]));
    EXPECT_GT(branches[1], branches[0] + branches[0] / 10) << "no path split past its first vertex";
    EXPECT_GT(branches[2], branches[1] + branches[1] / 10) << "lower windows past the first vertex split no more";
}

TEST(Analytic, SkySeenDirectlyAndThroughGlass)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // Camera looking up: half the view through a glass pane (L T (1 - R(theta)) per pixel), half
    // at the open sky (exactly L). Traced from the camera, so the only error is the camera
    // samples' spread over angles inside a pixel (a few 1e-4 here).
    test::SceneBuilder b;
    const glm::vec3 T(0.8f);
    b.add("pane", rect({-3, 2, -3}, {6, 0, 0}, {0, 0, 3}), b.glass("glass", T, 1.5f));
    b.uniformSky(3000.0);
    b.camera({0, 0, 0}, {0, 1, 0}, {0, 0, -1}, 60.0);
    const int W = 32, H = 32;
    Scene scene = b.build();
    const auto t = test::renderScene(*ctx, scene, W, H, 1u << 16, {});
    expectClean(t.result);
    const CameraSpec& cam = scene.cameras[0];
    int through = 0, open = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const double tanY = std::tan(cam.yfovRad / 2), tanX = tanY;
            const glm::dvec3 d = glm::normalize(cam.forward + (2.0 * (x + 0.5) / W - 1) * tanX * cam.right +
                                                (1.0 - 2.0 * (y + 0.5) / H) * tanY * cam.up);
            const glm::dvec3 hitPane = d * (2.0 / d.y);
            const double Lm = t.result.image.luminance(std::size_t(y) * W + x);
            if (hitPane.z < -0.1) {
                const double ci = d.y, ct = std::sqrt(1 - (1 - ci * ci) / 2.25);
                const double rs = (ci - 1.5 * ct) / (ci + 1.5 * ct), rp = (1.5 * ci - ct) / (1.5 * ci + ct);
                EXPECT_NEAR(Lm, 3000.0 * 0.8 * (1 - 0.5 * (rs * rs + rp * rp)), 3.0) << x << "," << y;
                ++through;
            } else if (hitPane.z > 0.1) {
                EXPECT_NEAR(Lm, 3000.0, 1e-3) << x << "," << y;
                ++open;
            }
        }
    EXPECT_GT(through, 300);
    EXPECT_GT(open, 300);
}

// A closed white box (every surface rho = 1) with a 0.9 x 0.9 m opening in its roof, under a
// uniform sky: at equilibrium every interior surface has the sky's luminance L -- the furnace
// test. A path escapes only through the opening (1/29 of the box's area), so paths bounce ~29
// times, and Russian roulette (which never fires at rho = 1) cannot end them: only the opening
// can. The default --max-bounces only guards against endless loops; a cap of 64 would remove
// ~11 % of the light, which the cut-flux counter must report.
Scene furnaceBox()
{
    test::SceneBuilder b;
    const float S = 2.0f, o0 = 0.55f, o1 = 1.45f;
    std::vector<Triangle> w;
    for (const auto& r : {rect({0, 0, 0}, {S, 0, 0}, {0, 0, S}),  // floor
                          rect({0, 0, 0}, {S, 0, 0}, {0, S, 0}), rect({0, 0, S}, {S, 0, 0}, {0, S, 0}),
                          rect({0, 0, 0}, {0, 0, S}, {0, S, 0}), rect({S, 0, 0}, {0, 0, S}, {0, S, 0}),
                          // roof around the opening
                          rect({0, S, 0}, {S, 0, 0}, {0, 0, o0}), rect({0, S, o1}, {S, 0, 0}, {0, 0, S - o1}),
                          rect({0, S, o0}, {o0, 0, 0}, {0, 0, o1 - o0}),
                          rect({o1, S, o0}, {S - o1, 0, 0}, {0, 0, o1 - o0})})
        w.insert(w.end(), r.begin(), r.end());
    b.add("box", w, b.material("white", glm::vec3(1.0f)));
    b.uniformSky(1000.0);
    b.camera({1.0, 1.0, 1.0}, {1.0, 0.0, 1.0}, {0, 0, -1}, 60.0);
    return b.build();
}

TEST(Analytic, FurnaceBoxIsUnbiasedByDefault)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const int W = 32, H = 32;
    const auto t = test::renderScene(*ctx, furnaceBox(), W, H, 4u << 20, {Roi{0, 0, W, H}});
    expectClean(t.result);
    std::printf("[ analytic ] furnace, default cap: %llu paths cut, flux share %.3g\n",
                static_cast<unsigned long long>(t.result.counts.maxBounceCuts), t.result.maxBounceFluxShare());
    EXPECT_LT(t.result.maxBounceFluxShare(), 1e-3);
    expectMean(t.result, 0, 1000.0, 0.01, "furnace box");
}

TEST(Analytic, FurnaceBoxReportsWhatACapRemoves)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const int W = 32, H = 32;
    const auto t = test::renderScene(*ctx, furnaceBox(), W, H, 4u << 20, {Roi{0, 0, W, H}}, 1, 64);
    expectClean(t.result);
    const double m = t.result.roiMean(0), se = t.result.roiMeanStdErr(0);
    // The flux entering through the opening: pi L A (a horizontal opening under a uniform sky).
    const double entering_lm = M_PI * 1000.0 * 0.9 * 0.9;
    const double cut_lm = t.result.counts.cutFlux / static_cast<double>(t.result.paths);
    std::printf("[ analytic ] furnace, cap 64: cut %.4f of the entering flux (%.4g of the emitted), floor "
                "%.4f of L (se %.2g)\n", cut_lm / entering_lm, t.result.maxBounceFluxShare(), m / 1000.0, se / 1000.0);
    EXPECT_GT(t.result.counts.maxBounceCuts, 0u);
    EXPECT_LT(m, 1000.0 - kSigmas * se) << "a cap of 64 removes light";
    // At rho = 1 every unit of flux in the box adds the same to the interior's luminance, so the
    // image falls short by the share of the entering flux the cap removed (up to the spatial shape
    // of the light still bouncing after 64 bounces, which is uniform well within this noise).
    EXPECT_NEAR(1.0 - m / 1000.0, cut_lm / entering_lm, kSigmas * se / 1000.0);
}

}  // namespace
}  // namespace fen
