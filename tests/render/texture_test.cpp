// texture_test.cpp — base-colour textures (kernels/lib/texture.h) against closed forms: a plane
// under a uniform sky has L = rho(x) L_sky at every point (it sees the whole sky, nothing else),
// so a textured plane shows each texel's decoded albedo times the sky. The plane's texture
// coordinates run from -1 to 2 in u and v, so each wrap mode (REPEAT, CLAMP_TO_EDGE,
// MIRRORED_REPEAT) paints its own pattern of the 2 x 2 texels over the 6 x 6 half-metre cells
// seen; each cell's mean is compared with its texel's value within 4 standard errors (from the 16
// batches). Bilinear filtering: on a clamped 2 x 1 texture the mean over a window centred between
// the texel centres is the average of the two (the filter is linear there), and the clamped ends
// are the texels themselves.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "support/cl_fixture.h"
#include "support/render_support.h"

namespace fen {
namespace {

constexpr double kSigmas = 4.0;
constexpr double kSky = 1000.0;   // cd/m^2
constexpr float kFactor = 0.9f;   // baseColorFactor, multiplying every texel

double srgbDecode(int code)
{
    const double c = code / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// A 3 x 3 m plane at y = 0, centred on the origin, textured with u = x + 0.5, v = z + 0.5 (so
// both run from -1 to 2), under a uniform sky, seen from straight above.
struct TexturedPlane {
    Scene scene;
    int W = 96, H = 96;
};

TexturedPlane texturedPlane(Texture tex)
{
    test::SceneBuilder b;
    const int m = b.material("textured", glm::vec3(kFactor));
    b.add("plane", test::rect({-1.5f, 0, -1.5f}, {3, 0, 0}, {0, 0, 3}), m);
    b.uniformSky(kSky);
    // 2 atan(1.5 * 1.05 / 4) = 43 deg: the plane fills the image, barely.
    b.camera({0, 4, 0}, {0, 0, 0}, {0, 0, -1}, 2.0 * std::atan(1.5 * 1.05 / 4.0) * 180.0 / M_PI);
    TexturedPlane p;
    p.scene = b.build();
    p.scene.textures.push_back(std::move(tex));
    p.scene.materials[static_cast<std::size_t>(m)].texture = 0;
    for (const Triangle& t : p.scene.triangles) {
        std::array<glm::vec2, 3> uv;
        const glm::vec3* v[3] = {&t.p0, &t.p1, &t.p2};
        for (int k = 0; k < 3; ++k)
            uv[static_cast<std::size_t>(k)] = glm::vec2(v[k]->x + 0.5f, v[k]->z + 0.5f);
        p.scene.triangleUv.push_back(uv);
    }
    return p;
}

// The pixels whose footprint lies inside the square [u0, u1] x [v0, v1] of texture space (shrunk
// by `margin`), as a rectangle of the image.
Roi pixelsInside(const TexturedPlane& p, double u0, double u1, double v0, double v1, double margin)
{
    Roi r{p.W, p.H, 0, 0};
    const CameraSpec& cam = p.scene.cameras.front();
    for (int y = 0; y < p.H; ++y)
        for (int x = 0; x < p.W; ++x) {
            bool inside = true;
            for (double dy : {0.0, 1.0})
                for (double dx : {0.0, 1.0}) {
                    const glm::dvec3 w = test::pixelOnPlaneY(cam, p.W, p.H, x + dx, y + dy, 0.0);
                    const double u = w.x + 0.5, v = w.z + 0.5;
                    inside = inside && u > u0 + margin && u < u1 - margin && v > v0 + margin && v < v1 - margin;
                }
            if (inside) {
                r.x0 = std::min(r.x0, x);
                r.y0 = std::min(r.y0, y);
                r.x1 = std::max(r.x1, x + 1);
                r.y1 = std::max(r.y1, y + 1);
            }
        }
    return r;
}

// The texel index a texture coordinate in cell [c/2, c/2 + 1/2) of a 2-texel side reads.
int nearestTexel(int cell, TextureWrap w)
{
    // cell k covers [k/2, k/2 + 1/2): texel index i = k before wrapping
    const int i = cell;
    if (w == TextureWrap::ClampToEdge)
        return std::clamp(i, 0, 1);
    if (w == TextureWrap::MirroredRepeat) {
        const int k = ((i % 4) + 4) % 4;
        return k < 2 ? k : 3 - k;
    }
    return ((i % 2) + 2) % 2;
}

class TextureWrapModes : public ::testing::TestWithParam<TextureWrap> {};

TEST_P(TextureWrapModes, EachCellShowsItsTexelTimesTheSky)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const int codes[2][2] = {{60, 200}, {120, 250}};  // [row][column], sRGB codes (grey)
    Texture tex;
    tex.name = "checker";
    tex.width = 2;
    tex.height = 2;
    for (int row = 0; row < 2; ++row)
        for (int col = 0; col < 2; ++col)
            for (int c = 0; c < 3; ++c)
                tex.rgb.push_back(static_cast<std::uint8_t>(codes[row][col]));
    tex.wrapS = tex.wrapT = GetParam();
    tex.nearest = true;
    const TexturedPlane p = texturedPlane(tex);
    std::vector<Roi> rois;
    std::vector<double> expected;
    for (int cv = -2; cv < 4; ++cv)
        for (int cu = -2; cu < 4; ++cu) {
            rois.push_back(pixelsInside(p, cu * 0.5, cu * 0.5 + 0.5, cv * 0.5, cv * 0.5 + 0.5, 0.05));
            ASSERT_GT(rois.back().x1 - rois.back().x0, 2);
            expected.push_back(kFactor * srgbDecode(codes[nearestTexel(cv, GetParam())][nearestTexel(cu, GetParam())]) *
                               kSky);
        }
    const auto t = test::renderScene(*ctx, p.scene, p.W, p.H, 24u << 20, rois);
    EXPECT_EQ(t.result.counts.badContributions, 0u);
    double worst = 0.0;
    for (std::size_t k = 0; k < rois.size(); ++k) {
        const double m = t.result.roiMean(k), se = t.result.roiMeanStdErr(k);
        worst = std::max(worst, std::abs(m - expected[k]) / se);
        EXPECT_NEAR(m, expected[k], kSigmas * se) << "cell " << k << ": " << m << " vs " << expected[k];
        EXPECT_LE(se, 0.03 * expected[k]) << "cell " << k << ": too noisy to test";
    }
    std::printf("[ texture ] 36 cells, worst deviation %.2f sigma\n", worst);
}

INSTANTIATE_TEST_SUITE_P(Modes, TextureWrapModes,
                         ::testing::Values(TextureWrap::Repeat, TextureWrap::ClampToEdge, TextureWrap::MirroredRepeat),
                         [](const auto& info) {
                             return info.param == TextureWrap::Repeat        ? std::string("repeat")
                                    : info.param == TextureWrap::ClampToEdge ? std::string("clamp")
                                                                             : std::string("mirror");
                         });

TEST(Texture, BilinearFilteringIsLinearBetweenTexelCentres)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    Texture tex;
    tex.name = "ramp";
    tex.width = 2;
    tex.height = 1;
    tex.rgb = {60, 60, 60, 200, 200, 200};
    tex.wrapS = tex.wrapT = TextureWrap::ClampToEdge;
    const TexturedPlane p = texturedPlane(tex);
    const double a = kFactor * srgbDecode(60) * kSky, b = kFactor * srgbDecode(200) * kSky;
    // u < 1/4 reads texel 0 alone, u > 3/4 texel 1 alone; in between, linear (in decoded values).
    const std::vector<Roi> rois = {pixelsInside(p, -1.0, 0.2, -0.5, 1.5, 0.05),
                                   pixelsInside(p, 0.4, 0.6, -0.5, 1.5, 0.0),
                                   pixelsInside(p, 0.8, 2.0, -0.5, 1.5, 0.05)};
    // The middle window must be symmetric about u = 1/2 for its mean to be the average.
    const CameraSpec& cam = p.scene.cameras.front();
    const glm::dvec3 left = test::pixelOnPlaneY(cam, p.W, p.H, rois[1].x0, 0, 0.0);
    const glm::dvec3 right = test::pixelOnPlaneY(cam, p.W, p.H, rois[1].x1, 0, 0.0);
    ASSERT_NEAR(left.x + right.x, 0.0, 1e-6) << "window not centred on u = 1/2";
    const auto t = test::renderScene(*ctx, p.scene, p.W, p.H, 8u << 20, rois);
    const double expected[3] = {a, 0.5 * (a + b), b};
    for (std::size_t k = 0; k < 3; ++k) {
        const double m = t.result.roiMean(k), se = t.result.roiMeanStdErr(k);
        std::printf("[ texture ] bilinear window %zu: %.4g vs %.4g, %+.2f sigma\n", k, m, expected[k],
                    (m - expected[k]) / se);
        EXPECT_NEAR(m, expected[k], kSigmas * se);
        EXPECT_LE(se, 0.02 * expected[k]);
    }
}

}  // namespace
}  // namespace fen
