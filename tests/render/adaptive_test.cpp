// adaptive_test.cpp — adaptive emission (DESIGN.md §3.3) renders what the other strategies render:
// on rooms lit only through their windows it agrees with uniform emission within 4 sigma of their
// combined standard error, over both bases; on the inner room it agrees with correctly marked
// portals -- and stays unbiased over a portal base marked wrongly (the gap under the door, or one
// window of two), where portal emission alone is biased low, because the disk keeps a share of
// the base density; a
// floor lit only through a small opening, which the first paths almost never find, converges to
// its closed form (no cell dies); the opening aim (DESIGN.md §3.5) keeps the courtyard's mean, lit
// by light reflected outside, and aims at its window's outer side; and the same seed gives the same
// image and the same learned grid whatever the pool size.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>

#include "scene/gltf_load.h"
#include "sky/sky_spec.h"
#include "support/cl_fixture.h"
#include "support/render_support.h"
#include "support/window_rooms.h"

namespace fen {
namespace {

using test::expectAgree;
using test::Measured;
using test::measure;
using test::rect;
using test::Windows;
using test::windowRoom;

EmissionSettings adaptive(EmissionMethod base, const std::string& portals = "")
{
    EmissionSettings e;
    e.method = EmissionMethod::Adaptive;
    e.adaptive.base = base;
    e.portals = portals;
    return e;
}

using Case = std::tuple<Windows, EmissionMethod>;

class AdaptiveUnbiased : public ::testing::TestWithParam<Case> {};

TEST_P(AdaptiveUnbiased, AgreesWithUniform)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const auto [room, base] = GetParam();
    const Scene scene = windowRoom(room);
    // One uniform reference per room for the whole suite.
    static std::map<Windows, Measured> uniform;
    if (!uniform.count(room))
        uniform[room] = measure(*ctx, scene, EmissionMethod::Uniform, 12u << 20);
    const Measured a = measure(*ctx, scene, adaptive(base), 3u << 20);
    expectAgree(a, uniform[room], base == EmissionMethod::Uniform ? "adaptive (uniform base) vs uniform"
                                                                  : "adaptive (portal base) vs uniform",
                "adaptive");
    EXPECT_LT(a.se, uniform[room].se) << "learning should beat uniform emission with 4x fewer paths";
}

std::string caseName(const ::testing::TestParamInfo<Case>& info)
{
    return test::windowRoomName(std::get<0>(info.param)) +
           (std::get<1>(info.param) == EmissionMethod::Uniform ? "_UniformBase" : "_PortalBase");
}

INSTANTIATE_TEST_SUITE_P(Rooms, AdaptiveUnbiased,
                         ::testing::Combine(::testing::Values(Windows::One, Windows::Two, Windows::InLine,
                                                              Windows::DeepFrame),
                                            ::testing::Values(EmissionMethod::Uniform, EmissionMethod::Portal)),
                         caseName);

// The inner room: the whole image -- the inner room lit through the gap, and the outer room seen
// through it. Light that reaches the camera only through a 5 cm gap makes a light tracer's
// estimate heavy-tailed (rare paths, large contributions): the comparisons ask for less precision
// than on the rooms above, still far more than the wrong portal's error (-59 %).
Scene innerRoom() { return loadGltf(std::string(FEN_SCENES_DIR) + "/inner_room.gltf"); }
const Roi kWhole{0, 0, 96, 72};

const Measured& innerReference(ocl::Context& ctx)
{
    static const Measured m =
        measure(ctx, innerRoom(), EmissionMethod::Portal, 8u << 20, PortalOverlap::Reject, "", 96, 72, kWhole);
    return m;
}

TEST(AdaptiveInnerRoom, AgreesWithCorrectPortalsOverEitherBase)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const Measured& ref = innerReference(*ctx);
    for (EmissionMethod base : {EmissionMethod::Uniform, EmissionMethod::Portal}) {
        const Measured a = measure(*ctx, innerRoom(), adaptive(base), 12u << 20, 96, 72, kWhole);
        expectAgree(a, ref, base == EmissionMethod::Uniform ? "inner room, adaptive (uniform base)"
                                                            : "inner room, adaptive (portal base)",
                    "adaptive", 0.08);
    }
}

TEST(AdaptiveInnerRoom, TheGapPortalStaysUnbiasedThroughTheDiskShare)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // Marking the gap instead of the window and the door: portal emission alone loses most of the
    // light (PortalFailure.TheGapUnderTheDoorLosesMostOfTheLight); over that base, adaptive
    // emission keeps a share of disk paths, learns where the light really comes from, and agrees.
    const Measured& ref = innerReference(*ctx);
    const Measured gap = measure(*ctx, innerRoom(), EmissionMethod::Portal, 4u << 20, PortalOverlap::Reject,
                                 "gap", 96, 72, kWhole);
    const Measured a = measure(*ctx, innerRoom(), adaptive(EmissionMethod::Portal, "gap"), 24u << 20, 96, 72, kWhole);
    expectAgree(a, ref, "inner room, adaptive over the gap portal", "adaptive", 0.25);
    std::printf("[ adaptive ] the gap portal alone: %.4g +- %.2g (%.2fx the reference)\n", gap.mean, gap.se,
                gap.mean / ref.mean);
    EXPECT_GT(ref.mean - gap.mean, 4.0 * std::hypot(ref.se, gap.se)) << "the gap portal alone must be low";
}

TEST(AdaptiveUnmarkedWindow, TheDiskShareFindsTheLightPortalsMiss)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // Two windows, only the south one marked: portal emission misses the east window's light;
    // adaptive emission over that portal base does not.
    const Scene scene = windowRoom(Windows::Two);
    const Measured u = measure(*ctx, scene, EmissionMethod::Uniform, 12u << 20);
    const Measured p = measure(*ctx, scene, EmissionMethod::Portal, 2u << 20, PortalOverlap::Reject, "south_pane");
    const Measured a = measure(*ctx, scene, adaptive(EmissionMethod::Portal, "south_pane"), 4u << 20);
    std::printf("[ adaptive ] south window marked only: portal %.5g +- %.3g, uniform %.5g +- %.3g\n", p.mean,
                p.se, u.mean, u.se);
    EXPECT_GT(u.mean - p.mean, 4.0 * std::hypot(u.se, p.se)) << "the unmarked window's light is missing";
    expectAgree(a, u, "adaptive over the south portal vs uniform", "adaptive");
}

TEST(AdaptiveRareLight, ASmallOpeningIsFoundAndItsFloorConverges)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // A black 1 x 1 x 0.6 m box with a 20 x 20 cm opening in its ceiling, on a 20 x 20 m black
    // ground, under a uniform sky: about 4 paths in 10^5 of the base density pass the opening, so
    // the first learning pass sees a handful. The floor under it: rho L F per pixel (F the
    // configuration factor to the opening, as in Analytic.FloorUnderAnOpeningInABlackRoom).
    test::SceneBuilder b;
    const int black = b.material("black", glm::vec3(0.0f));
    const float S = 1.0f, Hc = 0.6f, o0 = 0.4f, o1 = 0.6f;
    b.add("floor", rect({0, 0, 0}, {S, 0, 0}, {0, 0, S}), b.material("floor", glm::vec3(0.8f)));
    std::vector<Triangle> w = test::boxWithCeilingOpening(S, Hc, o0, o1);
    const auto ground = rect({-10, -0.01f, -10}, {20, 0, 0}, {0, 0, 20});
    w.insert(w.end(), ground.begin(), ground.end());
    b.add("box and ground", w, black);
    b.uniformSky(1000.0);
    b.camera({0.5, 0.55, 0.5}, {0.5, 0.0, 0.5}, {0, 0, -1}, 60.0);
    const Scene scene = b.build();
    const int W = 32, H = 24;
    const Roi roi{10, 8, 22, 16};
    const double expected = test::floorUnderOpeningMean(scene.cameras[0], W, H, roi, 0.8, 1000.0, Hc, o0, o1);
    const Measured a = measure(*ctx, scene, adaptive(EmissionMethod::Uniform), 6u << 20, W, H, roi);
    std::printf("[ adaptive ] small opening: measured %.5g +- %.3g, expected %.5g: %+.2f sigma\n", a.mean,
                a.se, expected, (a.mean - expected) / a.se);
    EXPECT_NEAR(a.mean, expected, 4.0 * a.se);
    EXPECT_LT(a.se, 0.02 * expected) << "the opening should have been found";
}

// The courtyard is lit by light that bounced outside before it got in: the opening aim sends the
// bounces outside at its one window. Unbiased: the mean agrees with uniform emission's within 4
// sigma; and it aims: at the same paths the mean's standard error is below adaptive's without it,
// and the aim holds the window's two triangles, aimed at from outside (side 1: the room is on the
// side its normal points to).
TEST(AdaptiveAim, TheCourtyardAgreesWithUniformAndTheAimSendsLightIn)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const Scene scene = loadGltf(std::string(FEN_SCENES_DIR) + "/courtyard.gltf");
    const Roi whole{0, 0, 48, 36};
    const Measured u = measure(*ctx, scene, EmissionMethod::Uniform, 12u << 20, PortalOverlap::Reject, "", 48, 36, whole);
    const Measured a = measure(*ctx, scene, adaptive(EmissionMethod::Uniform), 3u << 20, 48, 36, whole);
    EmissionSettings off = adaptive(EmissionMethod::Uniform);
    off.adaptive.aim.enabled = false;
    const Measured o = measure(*ctx, scene, off, 3u << 20, 48, 36, whole);
    expectAgree(a, u, "adaptive with the opening aim vs uniform", "aim");
    std::printf("[ aim      ] courtyard at 3M paths: standard error %.3g with the aim, %.3g without\n", a.se, o.se);
    EXPECT_LT(a.se, o.se);
    const nlohmann::json& aim = a.emission["aim"];
    EXPECT_EQ(aim.value("openings", 0), 1);
    EXPECT_EQ(aim.value("aimed_triangles", 0), 2);
    ASSERT_EQ(aim["aimed"].size(), 1u);
    EXPECT_EQ(aim["aimed"][0].value("side", -1), 1);
    EXPECT_EQ(o.emission["aim"].value("aimed_triangles", -1), 0);
}

// The aim's share at first vertices, learned, against fixed at 0.75: the courtyard's light reaches
// the camera mostly by leaving its walls and ground towards the window, so the share it learns is
// below 0.75 and, at the same paths, the mean's standard error is below the fixed share's;
// unbiased both ways (within 4 sigma of uniform emission).
TEST(AdaptiveAim, TheLearnedShareAimsMoreInTheCourtyardAndStaysUnbiased)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const Scene scene = loadGltf(std::string(FEN_SCENES_DIR) + "/courtyard.gltf");
    const Roi whole{0, 0, 48, 36};
    const Measured u = measure(*ctx, scene, EmissionMethod::Uniform, 12u << 20, PortalOverlap::Reject, "", 48, 36, whole);
    EmissionSettings learning = adaptive(EmissionMethod::Uniform);
    learning.adaptive.aim.learnShare = true;
    const Measured learned = measure(*ctx, scene, learning, 3u << 20, 48, 36, whole);
    EmissionSettings fixed = adaptive(EmissionMethod::Uniform);
    fixed.adaptive.aim.learnShare = false;
    fixed.adaptive.aim.cosineShare = 0.75;
    const Measured f = measure(*ctx, scene, fixed, 3u << 20, 48, 36, whole);
    expectAgree(f, u, "adaptive with the aim's share fixed at 0.75 vs uniform", "aim fixed");
    expectAgree(learned, u, "adaptive with the aim's first share learned vs uniform", "aim learned");
    const double share = learned.emission["aim"].value("first_share", 1.0);
    std::printf("[ aim      ] courtyard at 3M paths: standard error %.3g with the share learned (%.3g), %.3g at 0.75\n",
                learned.se, share, f.se);
    EXPECT_TRUE(learned.emission["aim"].value("share_learned", false));
    EXPECT_LT(share, 0.75);
    EXPECT_GE(share, 0.25);
    EXPECT_LT(learned.se, f.se);
    EXPECT_DOUBLE_EQ(f.emission["aim"].value("first_share", 0.0), 0.75);
    EXPECT_DOUBLE_EQ(learned.emission["aim"].value("cosine_share", 0.0), 0.75) << "past the first vertex";
}

TEST(AdaptiveDeterminism, SameSeedSameImageAndGridWhateverThePool)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const Scene scene = loadGltf(std::string(FEN_SCENES_DIR) + "/room.gltf");
    const auto sky = buildSky(scene.sky);
    auto render = [&](std::uint32_t pool) {
        RenderSettings s;
        s.emission = adaptive(EmissionMethod::Uniform);
        s.paths = 1u << 21;
        s.seed = 7;
        s.poolSize = pool;
        Renderer r(*ctx, scene, sky, scene.cameras.at(0), 64, 48, s);
        return r.render();
    };
    const RenderResult a = render(1u << 16), b = render(1u << 13);
    ASSERT_EQ(a.image.rgb.size(), b.image.rgb.size());
    EXPECT_EQ(0, std::memcmp(a.image.rgb.data(), b.image.rgb.data(), a.image.rgb.size() * 4));
    EXPECT_EQ(a.emission["checksum"], b.emission["checksum"]) << "the learned grid must not depend on the pool";
    EXPECT_EQ(a.emission["cells"], b.emission["cells"]);
    EXPECT_GT(a.emission["passes"].get<int>(), 3);
    EXPECT_GT(a.emission["deepest"].get<int>(), a.emission["initial_depth"].get<int>()) << "nothing was refined";
}

}  // namespace
}  // namespace fen
