// opening_walk_test.cpp — the openings' walks (kernels/lib/opening_walk.h, DESIGN.md §3.6,
// --adaptive-openings-share), rendered against adaptive emission without them.
//   - Unbiased: the courtyard, lit almost wholly by light that bounced outside, keeps its mean
//     within 4 sigma. The two parts are disjoint: were the light that reached the pane after a
//     bounce counted by both the walks and the light paths (weighing 1 / (1 - S) = 10), the mean
//     would be about twice; by neither, near nothing. The window box of the room (sky and sun
//     straight in, which the walks and the light paths share between them) keeps its mean too.
//   - The walks take their share: about S of the path indices once the aim lists a pane (the
//     first pass has none), each tracing its way outwards.
//   - The same seed renders the same bytes at another pool size (which slot traces which path).
//   - Their share raced (auto, host/emission/openings_race.h): on in the courtyard, off in the room,
//     each keeping its mean.
// Fused and wavefront kernels agree bit for bit: fused_test.cpp. Bad options: cli_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "render/renderer.h"
#include "scene/gltf_load.h"
#include "sky/sky_spec.h"
#include "support/cl_fixture.h"

namespace fen {
namespace {

// share < 0: auto, raced in passes of 2^17 paths or more
RenderResult renderScene(ocl::Context& ctx, const char* name, double share, std::uint64_t paths, std::uint32_t seed,
                         KernelMode mode = KernelMode::Fused, std::uint32_t pool = 0)
{
    const Scene scene = loadGltf(std::string(FEN_SCENES_DIR) + "/" + name);
    const auto sky = buildSky(scene.sky);
    RenderSettings s;
    s.emission.method = EmissionMethod::Adaptive;
    s.emission.adaptive.openingsShare = std::max(share, 0.0);
    s.emission.adaptive.openingsAuto = share < 0.0;
    s.emission.adaptive.openingsRacePaths = std::uint64_t{1} << 17;
    s.paths = paths;
    s.seed = seed;
    s.kernels = mode;
    s.poolSize = pool;
    s.rois = {Roi{0, 0, 64, 48}};
    Renderer r(ctx, scene, sky, scene.cameras.at(0), 64, 48, s);
    return r.render();
}

void expectSameMean(const RenderResult& a, const RenderResult& b, const char* what)
{
    const double ma = a.roiMean(0), mb = b.roiMean(0);
    const double sa = a.roiMeanStdErr(0), sb = b.roiMeanStdErr(0);
    // 4 sigma of the difference of two independent estimates
    EXPECT_LT(std::abs(ma - mb), 4.0 * std::sqrt(sa * sa + sb * sb)) << what << ": " << ma << " +- " << sa
                                                                      << " without the walks, " << mb << " +- " << sb
                                                                      << " with them";
    EXPECT_GT(mb, 0.0) << what;
    EXPECT_EQ(b.counts.badContributions, 0u) << what;
}

TEST(OpeningWalks, KeepTheCourtyardsMeanAndTakeTheirShare)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const std::uint64_t paths = 4000000;
    const RenderResult today = renderScene(*ctx, "courtyard.gltf", 0.0, paths, 1);
    const RenderResult walks = renderScene(*ctx, "courtyard.gltf", 0.9, paths, 1);
    expectSameMean(today, walks, "courtyard");
    EXPECT_EQ(today.counts.openingWalks, 0u);
    // S of the indices once the aim lists the window (from the second pass of 2^16 paths on)
    EXPECT_GT(walks.counts.openingWalks, static_cast<std::uint64_t>(0.85 * static_cast<double>(paths)));
    EXPECT_LT(walks.counts.openingWalks, static_cast<std::uint64_t>(0.9 * static_cast<double>(paths)));
    // at least a look outwards each, a sun ray where it lands lit
    EXPECT_GT(walks.counts.openingWalkRays, 2 * walks.counts.openingWalks);
}

TEST(OpeningWalks, KeepTheRoomsMean)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const std::uint64_t paths = 2000000;
    expectSameMean(renderScene(*ctx, "room.gltf", 0.0, paths, 2), renderScene(*ctx, "room.gltf", 0.5, paths, 2),
                   "room");
}

// The share raced (--adaptive-openings-share auto): on in the courtyard, at the largest share, with its
// mean. In the room the race decides too, and whatever it decides (in passes this small it is not
// always right: docs/results/guiding.md measures the default's), the mean holds.
TEST(OpeningWalks, AutoTakesThemWhereTheyPayAndKeepsTheMean)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const std::uint64_t paths = 4000000;
    const RenderResult today = renderScene(*ctx, "courtyard.gltf", 0.0, paths, 1);
    const RenderResult raced = renderScene(*ctx, "courtyard.gltf", -1.0, paths, 1);
    expectSameMean(today, raced, "courtyard, raced");
    const nlohmann::json& race = raced.emission["openings_race"];
    EXPECT_EQ(race["phase"], "decided");
    EXPECT_NEAR(race["share"].get<double>(), 0.95, 1e-9) << race.dump();
    EXPECT_GE(race["predicted_gain"].get<double>(), 1.25) << race.dump();
    // most paths after the race are walks: more than half of all
    EXPECT_GT(raced.counts.openingWalks, paths / 2);

    // batches of 2.5 10^5 paths: a pass of 2^17 or more races
    const RenderResult room = renderScene(*ctx, "room.gltf", -1.0, paths, 2);
    const nlohmann::json& roomRace = room.emission["openings_race"];
    EXPECT_EQ(roomRace["phase"], "decided");
    EXPECT_GT(room.counts.openingWalks, 0u);  // the trial's half pass at least
    if (roomRace["share"].get<double>() == 0.0) {
        EXPECT_LT(room.counts.openingWalks, paths / 10) << "walks after a decision against them";
    }
    expectSameMean(renderScene(*ctx, "room.gltf", 0.0, paths, 2), room, "room, raced");
}

TEST(OpeningWalks, TheSameSeedGivesTheSameBytesAtAnyPoolSize)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const RenderResult a = renderScene(*ctx, "courtyard.gltf", 0.9, 1u << 19, 5, KernelMode::Wavefront, 1u << 16);
    const RenderResult b = renderScene(*ctx, "courtyard.gltf", 0.9, 1u << 19, 5, KernelMode::Wavefront, 1u << 14);
    ASSERT_EQ(a.image.rgb.size(), b.image.rgb.size());
    EXPECT_EQ(0, std::memcmp(a.image.rgb.data(), b.image.rgb.data(), a.image.rgb.size() * 4));
    EXPECT_EQ(a.counts.openingWalks, b.counts.openingWalks);
    EXPECT_EQ(a.counts.openingWalkRays, b.counts.openingWalkRays);
    EXPECT_GT(a.counts.openingWalks, 0u);
}

}  // namespace
}  // namespace fen
