// camera_pass_test.cpp — the camera pass with its samples balanced per pixel
// (render/camera_sampler.h, kernels/camera_pass.cl):
//  - unbiased: looking up from inside a black box at an opening in its ceiling, every pixel shows
//    the sky's luminance times the share of its footprint inside the opening (the ceiling plane is
//    parallel to the image plane, so the footprint is a rectangle); the opening's box and each of
//    its four edges' strips of pixels (where the counts vary the most) agree with that within 4
//    sigma of their batch standard error;
//  - converging: with the box grey, the noise of the edge pixels falls by about 2 when the light
//    paths are 4 times as many (>= 1.7 required), where with a fixed sample per pixel and batch
//    it stays near 1 (the defect balanced sampling removes; checked too, so that the test can fail).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "support/cl_fixture.h"
#include "support/render_support.h"

namespace fen {
namespace {

constexpr float kS = 4.0f, kH = 3.0f;                       // the box (m)
constexpr float kX0 = 1.45f, kX1 = 2.55f, kZ0 = 1.6f, kZ1 = 2.5f;  // the opening: edges off the pixel grid
constexpr double kSkyL = 1000.0;                             // cd/m^2
constexpr int kW = 48, kH_px = 48;

Scene openingScene(float albedo)
{
    test::SceneBuilder b;
    const int m = b.material("inside", glm::vec3(albedo));
    b.add("box", test::boxWithCeilingOpening(kS, kH, kX0, kX1, kZ0, kZ1), m);
    b.add("floor", test::rect({0, 0, 0}, {0, 0, kS}, {kS, 0, 0}), m);
    b.uniformSky(kSkyL);
    b.camera({2.0, 0.4, 2.0}, {2.0, 3.0, 2.0}, {0, 0, -1}, 60.0);
    return b.build();
}

// The share of pixel (x, y)'s footprint on the ceiling plane inside the opening.
double coverage(const CameraSpec& cam, int x, int y)
{
    const glm::dvec3 a = test::pixelOnPlaneY(cam, kW, kH_px, x, y, kH);
    const glm::dvec3 b = test::pixelOnPlaneY(cam, kW, kH_px, x + 1, y + 1, kH);
    const auto overlap = [](double p, double q, double lo, double hi) {
        return std::max(0.0, std::min(std::max(p, q), hi) - std::max(std::min(p, q), lo));
    };
    const double area = std::abs(b.x - a.x) * std::abs(b.z - a.z);
    return overlap(a.x, b.x, kX0, kX1) * overlap(a.z, b.z, kZ0, kZ1) / area;
}

// The opening's bounding box of pixels and the strips of pixels its four edges cross.
struct Regions {
    std::vector<Roi> rois;  // [0] the box, [1..4] the edges' strips
};
Regions openingRegions(const CameraSpec& cam)
{
    int x0 = kW, y0 = kH_px, x1 = -1, y1 = -1;
    for (int y = 0; y < kH_px; ++y)
        for (int x = 0; x < kW; ++x)
            if (coverage(cam, x, y) > 0.0) {
                x0 = std::min(x0, x);
                y0 = std::min(y0, y);
                x1 = std::max(x1, x);
                y1 = std::max(y1, y);
            }
    EXPECT_GT(x1 - x0, 8);
    EXPECT_GT(y1 - y0, 8);
    // Every outermost row and column is partly covered (the edges lie off the pixel grid).
    return {{Roi{x0, y0, x1 + 1, y1 + 1}, Roi{x0, y0 + 1, x0 + 1, y1}, Roi{x1, y0 + 1, x1 + 1, y1},
             Roi{x0 + 1, y0, x1, y0 + 1}, Roi{x0 + 1, y1, x1, y1 + 1}}};
}

double exactMean(const CameraSpec& cam, const Roi& r)
{
    double s = 0.0;
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x)
            s += kSkyL * coverage(cam, x, y);
    return s / static_cast<double>(r.pixels());
}

// RMS over ROI k of each pixel's standard error.
double noise(const RenderResult& r, const Roi& roi)
{
    double s = 0.0;
    for (int y = roi.y0; y < roi.y1; ++y)
        for (int x = roi.x0; x < roi.x1; ++x) {
            const double e = r.stdErrLuminance[static_cast<std::size_t>(y) * kW + x];
            s += e * e;
        }
    return std::sqrt(s / static_cast<double>(roi.pixels()));
}

TEST(CameraPass, BalancedSamplesAreUnbiasedAtTheEdges)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const Scene scene = openingScene(0.0f);  // black: the image is the camera pass's alone
    const CameraSpec& cam = scene.cameras[0];
    const Regions g = openingRegions(cam);
    const auto t = test::renderScene(*ctx, scene, kW, kH_px, 1u << 20, g.rois);
    const RenderResult& r = t.result;
    EXPECT_EQ(r.cameraPass["mode"], "balanced");
    EXPECT_GT(r.cameraPass["max_samples_per_pixel"].get<std::uint32_t>(), 16u) << r.cameraPass.dump();
    EXPECT_GT(r.cameraPass["pixels_above_floor"].get<std::uint64_t>(), 40u) << r.cameraPass.dump();
    const char* names[] = {"box", "left", "right", "top", "bottom"};
    for (std::size_t k = 0; k < g.rois.size(); ++k) {
        const double want = exactMean(cam, g.rois[k]);
        const double got = r.roiMean(k), se = r.roiMeanStdErr(k);
        std::printf("[ camera   ] %-6s %.3f exact %.3f (%+.2f sigma, se %.2g)\n", names[k], got, want,
                    (got - want) / se, se);
        ASSERT_GT(se, 0.0);
        EXPECT_NEAR(got, want, 4.0 * se) << names[k];
    }
}

TEST(CameraPass, BalancedEdgeNoiseFallsWithTheLightPaths)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const Scene scene = openingScene(0.5f);
    const Regions g = openingRegions(scene.cameras[0]);
    double ratio[2];
    for (const CameraPassMode mode : {CameraPassMode::Balanced, CameraPassMode::Fixed}) {
        const auto tweak = [&](RenderSettings& s) { s.cameraPass = mode; };
        const auto lo = test::renderScene(*ctx, scene, kW, kH_px, 1u << 18, g.rois, 1, 1024, tweak);
        const auto hi = test::renderScene(*ctx, scene, kW, kH_px, 1u << 20, g.rois, 1, 1024, tweak);
        const double nLo = noise(lo.result, g.rois[0]), nHi = noise(hi.result, g.rois[0]);
        for (std::size_t k = 1; k < g.rois.size(); ++k)
            std::printf("[ camera   ]   strip %zu: %.3g -> %.3g\n", k, noise(lo.result, g.rois[k]), noise(hi.result, g.rois[k]));
        ratio[mode == CameraPassMode::Fixed] = nLo / nHi;
        std::printf("[ camera   ] %s: opening's noise %.3g -> %.3g cd/m2 with 4x the paths (%.2fx), samples %.3g -> %.3g "
                    "per pixel\n",
                    cameraPassModeName(mode).c_str(), nLo, nHi, nLo / nHi, lo.result.cameraSamplesPerPixel,
                    hi.result.cameraSamplesPerPixel);
    }
    // 1/sqrt(effort): 2 expected; each figure pools some 80 pixels' estimates from 16 batches.
    EXPECT_GE(ratio[0], 1.7) << "balanced: the edges' noise must fall with the light tracer's";
    EXPECT_LT(ratio[1], 1.3) << "fixed: one sample a batch should not have converged (else this test shows nothing)";
}

}  // namespace
}  // namespace fen
