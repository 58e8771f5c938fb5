// checkpoint_test.cpp — a render stopped after some batches, saved (render/checkpoint.h) and
// resumed gives the image, batch statistics, counters and learned emission grid of the render that
// was never stopped, bit for bit: for each strategy, with --paths and with --time's batch sizes.
// A checkpoint of another render is refused.
#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <fstream>

#include "render/renderer.h"
#include "scene/gltf_load.h"
#include "sky/sky_spec.h"
#include "support/cl_fixture.h"
#include "support/gltf_writer.h"
#include "util/error.h"

namespace fen {
namespace {

struct Case {
    const char* name;
    const char* scene;
    EmissionMethod method;
    EmissionMethod base;
    bool guide = false;
    bool window = false;
    double openingsShare = 0.0;  // the openings' walks (lib/opening_walk.h)
    bool openingsAuto = false;   // ... their share raced (host/emission/openings_race.h), in small passes
};

RenderResult renderCase(ocl::Context& ctx, const Case& c, const std::string& checkpoint, const std::string& resume,
                        int stopAfter, nlohmann::json* carry = nullptr, std::uint32_t seed = 3)
{
    const Scene scene = loadGltf(std::string(FEN_SCENES_DIR) + "/" + c.scene);
    const auto sky = buildSky(scene.sky);
    RenderSettings s;
    s.emission.method = c.method;
    s.emission.adaptive.base = c.base;
    s.emission.adaptive.firstPass = 1u << 14;  // several passes, so the grid learns across batches
    s.emission.adaptive.guide.enabled = c.guide;
    s.emission.adaptive.guide.minConnections = 4.0;
    s.emission.adaptive.guide.minGain = 1.0;  // tables in use wherever anything was seen
    s.emission.adaptive.guide.window = c.window;
    s.emission.adaptive.guide.windowRule = GuideOptions::WindowRule::Moment;
    s.emission.adaptive.guide.windowMinVisits = 16.0;
    s.emission.adaptive.guide.windowMinSurvival = 0.25;
    s.emission.adaptive.openingsShare = c.openingsShare;
    s.emission.adaptive.openingsAuto = c.openingsAuto;
    s.emission.adaptive.openingsRacePaths = std::uint64_t{1} << 16;
    s.paths = 1u << 20;
    s.seed = seed;
    s.rois = {Roi{8, 8, 40, 28}};
    s.checkpointPath = checkpoint;
    s.checkpointBatches = 1;
    s.resumePath = resume;
    s.carry = carry;
    std::atomic<bool> stop{false};
    s.stop = &stop;
    s.onBatch = [&](const BatchProgress& p) {
        if (carry)
            carry->push_back(p.batches);
        if (p.batches == stopAfter)
            stop = true;
    };
    Renderer r(ctx, scene, sky, scene.cameras.at(0), 48, 36, s);
    return r.render();
}

class Checkpoint : public ::testing::TestWithParam<Case> {};

TEST_P(Checkpoint, ResumedRenderIsBitIdentical)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const Case& c = GetParam();
    const std::string dir = test::tempDir(std::string("checkpoint-") + c.name);
    const RenderResult whole = renderCase(*ctx, c, "", "", -1);
    nlohmann::json carry = nlohmann::json::array();
    const RenderResult first = renderCase(*ctx, c, dir + "/c.ckpt", "", 5, &carry);
    EXPECT_TRUE(first.interrupted);
    EXPECT_EQ(first.batches, 5);
    EXPECT_EQ(first.checkpoints, 5);  // every batch (checkpointBatches = 1)
    nlohmann::json carried = nlohmann::json::array({"replaced"});
    const RenderResult rest = renderCase(*ctx, c, dir + "/c.ckpt", dir + "/c.ckpt", -1, &carried);
    EXPECT_FALSE(rest.interrupted);
    EXPECT_EQ(rest.resumedBatches, 5);
    EXPECT_EQ(rest.batches, whole.batches);
    EXPECT_EQ(rest.paths, whole.paths);
    // The caller's state came back and went on.
    EXPECT_EQ(carried, nlohmann::json::array({1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16}));
    ASSERT_EQ(rest.image.rgb.size(), whole.image.rgb.size());
    EXPECT_EQ(0, std::memcmp(rest.image.rgb.data(), whole.image.rgb.data(), whole.image.rgb.size() * 4));
    EXPECT_EQ(rest.stdErrLuminance, whole.stdErrLuminance);
    EXPECT_EQ(rest.roiBatchMeans, whole.roiBatchMeans);
    EXPECT_EQ(rest.batchWeights, whole.batchWeights);
    EXPECT_EQ(rest.counts.extensionRays, whole.counts.extensionRays);
    EXPECT_EQ(rest.counts.shadowRays, whole.counts.shadowRays);
    EXPECT_EQ(rest.counts.cutFlux, whole.counts.cutFlux);
    EXPECT_EQ(rest.counts.diffuseVertices, whole.counts.diffuseVertices);
    EXPECT_EQ(rest.counts.guidedVertices, whole.counts.guidedVertices);
    EXPECT_EQ(rest.counts.splitBranches, whole.counts.splitBranches);
    EXPECT_EQ(rest.counts.windowCulls, whole.counts.windowCulls);
    EXPECT_EQ(rest.counts.openingWalks, whole.counts.openingWalks);
    EXPECT_EQ(rest.counts.openingWalkRays, whole.counts.openingWalkRays);
    if (c.openingsShare > 0.0 || c.openingsAuto) {
        EXPECT_GT(whole.counts.openingWalks, 0u);
        EXPECT_EQ(rest.emission["openings_race"], whole.emission["openings_race"]);
    }
    if (c.window) {
        EXPECT_GT(whole.counts.splitBranches, 0u);
        EXPECT_EQ(rest.emission["guide"]["window_target"], whole.emission["guide"]["window_target"]);
        EXPECT_EQ(rest.emission["guide"]["window_slots"], whole.emission["guide"]["window_slots"]);
    }
    if (c.method == EmissionMethod::Adaptive) {
        EXPECT_EQ(rest.emission["checksum"], whole.emission["checksum"]);
        EXPECT_EQ(rest.emission["cells"], whole.emission["cells"]);
        EXPECT_EQ(rest.emission["passes"], whole.emission["passes"]);
        EXPECT_EQ(rest.emission["batch_weights"], whole.emission["batch_weights"]);
    }
    if (c.method == EmissionMethod::Portal) {
        EXPECT_EQ(rest.emission["unreached"], whole.emission["unreached"]);
    }
}

INSTANTIATE_TEST_SUITE_P(
    Strategies, Checkpoint,
    ::testing::Values(Case{"uniform", "room.gltf", EmissionMethod::Uniform, EmissionMethod::Uniform},
                      Case{"portal", "room.gltf", EmissionMethod::Portal, EmissionMethod::Uniform},
                      Case{"adaptive", "room.gltf", EmissionMethod::Adaptive, EmissionMethod::Uniform},
                      Case{"adaptive_portal", "inner_room.gltf", EmissionMethod::Adaptive, EmissionMethod::Portal},
                      Case{"adaptive_guide", "room.gltf", EmissionMethod::Adaptive, EmissionMethod::Uniform, true},
                      Case{"adaptive_window", "room.gltf", EmissionMethod::Adaptive, EmissionMethod::Uniform, true,
                           true},
                      // the walks start once the aim lists the window, a pass or two in
                      Case{"adaptive_openings", "courtyard.gltf", EmissionMethod::Adaptive, EmissionMethod::Uniform,
                           true, true, 0.9},
                      Case{"adaptive_openings_auto", "courtyard.gltf", EmissionMethod::Adaptive, EmissionMethod::Uniform,
                           true, true, 0.0, true}),
    [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

TEST(Checkpoint, AnotherRenderIsRefused)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const std::string dir = test::tempDir("checkpoint-refused");
    const Case c{"uniform", "room.gltf", EmissionMethod::Uniform, EmissionMethod::Uniform};
    renderCase(*ctx, c, dir + "/c.ckpt", "", 2);
    const auto refused = [&](const Case& other, std::uint32_t seed, const std::string& fragment) {
        try {
            renderCase(*ctx, other, "", dir + "/c.ckpt", -1, nullptr, seed);
            ADD_FAILURE() << "resumed a checkpoint of another render";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
        }
    };
    refused(c, 4, "seed was 3, not 4");
    refused({"portal", "room.gltf", EmissionMethod::Portal, EmissionMethod::Uniform}, 3,
            "method was \"uniform\", not \"portal\"");
    refused({"uniform", "inner_room.gltf", EmissionMethod::Uniform, EmissionMethod::Uniform}, 3, "the scene differs");
    // One byte altered anywhere: the checksum catches it.
    std::string bytes;
    {
        std::ifstream in(dir + "/c.ckpt", std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    ASSERT_GT(bytes.size(), 1000u);
    for (std::size_t at : {bytes.size() / 2, bytes.size() - 20}) {
        std::string bad = bytes;
        bad[at] ^= 0x01;
        std::ofstream(dir + "/c.ckpt", std::ios::binary) << bad;
        refused(c, 3, "damaged");
    }
    std::ofstream(dir + "/c.ckpt", std::ios::binary) << bytes.substr(0, bytes.size() / 3);
    refused(c, 3, "damaged");
    std::ofstream(dir + "/c.ckpt", std::ios::binary) << "P6\n48 36\n255\n";
    refused(c, 3, "not a fenestra checkpoint");
}

}  // namespace
}  // namespace fen
