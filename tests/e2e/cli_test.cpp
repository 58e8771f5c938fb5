// cli_test.cpp — the fenestra binary as a user meets it: bad input gives one line on stderr,
// starting "fenestra: error:", naming the file/option at fault, and a non-zero exit; never a
// crash. Plus a smoke run of `devices` and `bench --json`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "e2e/cli_run.h"
#include "support/gltf_writer.h"

namespace fen {
namespace {

using test::CliRun;
using test::expectError;
using test::run;
using test::slurp;

TEST(Cli, DevicesListsAtLeastOne)
{
    const CliRun r = run("devices --json");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_GE(j.size(), 1u);
    EXPECT_TRUE(j[0].contains("device"));
}

TEST(Cli, MissingSceneFile) { expectError(run("bench /no/such/scene.gltf"), 1, "/no/such/scene.gltf"); }

TEST(Cli, MalformedScene)
{
    const std::string path = test::tempDir("cli-bad") + "/broken.gltf";
    std::ofstream(path) << "{\"asset\":{\"version\":\"2.0\"},\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":9}}]}],"
                           "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]}";
    expectError(run("bench " + path + " --rays 1000 --runs 1 --no-embree"), 1, path);
}

TEST(Cli, UnknownDevice)
{
    expectError(run("bench --device no-such-device --rays 1000"), 1, "'no-such-device'");
    expectError(run("bench --device 99 --rays 1000"), 1, "index 99");
    // The work-group size knob is checked before any launch (README "Kernels and OpenCL").
    expectError(run("bench --rays 1000 --runs 1 --no-embree", "FEN_LOCAL_SIZE=48"), 1, "FEN_LOCAL_SIZE '48'");
    expectError(run("bench --rays 1000 --runs 1 --no-embree", "FEN_LOCAL_SIZE=2048"), 1, "power of two");
}

TEST(Cli, NoOpenClPlatform)
{
    // The ICD loader reads drivers from OCL_ICD_VENDORS: an empty directory means none at all.
    const std::string empty = test::tempDir("cli-noicd");
    expectError(run("devices", "OCL_ICD_VENDORS=" + empty), 1, "no OpenCL platform");
    expectError(run("bench --rays 1000", "OCL_ICD_VENDORS=" + empty), 1, "no OpenCL platform");
}

TEST(Cli, UsageErrors)
{
    expectError(run(""), 2, "subcommand");
    expectError(run("frobnicate"), 2, "frobnicate");
    expectError(run("bench --bogus"), 2, "--bogus");
    expectError(run("bench --layout bvh3"), 1, "bvh3");
    expectError(run("bench --rays 0"), 1, "--rays");
}

TEST(Cli, BenchJsonSmoke)
{
    const CliRun r = run("bench --rays 20000 --runs 1 --warmup 0 --layout all --json");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j["layouts"].size(), 3u);
    for (const auto& l : j["layouts"]) {
        EXPECT_GT(l["closest_mrays_s"]["median"].get<double>(), 0.0);
        EXPECT_GT(l["any_mrays_s"]["median"].get<double>(), 0.0);
        if (l.contains("closest_agreement_with_embree")) {
            EXPECT_GE(l["closest_agreement_with_embree"].get<double>(), 0.9999);
            EXPECT_GE(l["any_agreement_with_embree"].get<double>(), 0.9999);
            // both Embree modes timed, so both ratios are real numbers
            EXPECT_GT(l["closest_over_embree_robust"]["median"].get<double>(), 0.0);
            EXPECT_GT(l["any_over_embree_robust"]["median"].get<double>(), 0.0);
            EXPECT_GT(j["embree"]["robust"]["closest_mrays_s"]["median"].get<double>(), 0.0);
        }
    }
    EXPECT_GT(j["scene"]["triangles"].get<int>(), 100000);
    // --render: the render's record says how it ended its paths
    const CliRun rr = run("bench " + std::string(FEN_SCENES_DIR) + "/room.gltf --rays 20000 --runs 1 --warmup 0 "
                          "--no-embree --render --render-paths 20000 --json");
    ASSERT_EQ(rr.status, 0) << rr.err;
    const auto jr = nlohmann::json::parse(rr.out);
    EXPECT_EQ(jr["render"]["method"], "uniform");
    EXPECT_EQ(jr["render"]["roulette_depth"], 5);
    EXPECT_GT(jr["render"]["paths"].get<std::uint64_t>(), 0u);
    // the procedural room's window is a marked portal, so every method benchmarks there
    const CliRun rp = run("bench --rays 20000 --runs 1 --warmup 0 --no-embree --render "
                          "--render-method portal --render-paths 20000 --json");
    ASSERT_EQ(rp.status, 0) << rp.err;
    const auto jp = nlohmann::json::parse(rp.out);
    EXPECT_EQ(jp["render"]["method"], "portal");
    EXPECT_EQ(jp["render"]["scene"], "room (procedural) with a window");
    EXPECT_GT(jp["render"]["extension_rays"].get<std::uint64_t>(), 0u);
}

// A minimal valid scene for the render CLI: one plate, a camera, a uniform sky.
test::GltfWriter plateScene()
{
    test::GltfWriter w;
    w.addMeshNode("plate", {{{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}}, {{-1, 0, -1}, {1, 0, 1}, {-1, 0, 1}}});
    w.doc()["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
    w.doc()["nodes"].push_back({{"name", "cam"}, {"camera", 0}, {"translation", {0, 3, 0}},
                               {"rotation", {-0.7071067811865476, 0, 0, 0.7071067811865476}}});
    w.doc()["scenes"][0]["nodes"].push_back(1);
    w.doc()["scenes"][0]["extras"] = {{"sky", {{"type", "uniform"}, {"luminance", 1000}}}};
    return w;
}

TEST(CliRender, WritesExrPngAndJson)
{
    const std::string dir = test::tempDir("cli-render");
    const std::string scene = plateScene().write(dir + "/plate.gltf");
    // The output folder does not exist yet: it is created (a fresh clone has no out/).
    const CliRun r = run("render " + scene + " --out " + dir + "/new/out.exr --paths 200000 --width 40 --no-progress");
    ASSERT_EQ(r.status, 0) << r.err;
    for (const char* f : {"/new/out.exr", "/new/out.png", "/new/out.json", "/new/out.noise.exr"})
        EXPECT_FALSE(slurp(dir + f).empty()) << f;
    const auto j = nlohmann::json::parse(slurp(dir + "/new/out.json"));
    EXPECT_EQ(j["width"], 40);
    EXPECT_EQ(j["height"], 30);  // 4:3 when the camera gives no aspect ratio
    EXPECT_EQ(j["counters"]["bad_contributions"], 0);
    EXPECT_EQ(j["counters"]["fixed_point_overflows"], 0);
    EXPECT_GT(j["mean_luminance_cd_m2"].get<double>(), 0.0);
    for (const char* k : {"paths", "rays", "seconds", "rays_per_second", "paths_per_second",
                          "rms_luminance_cd_m2", "noise_std_err_cd_m2", "noise_top1_share", "mean_std_err_cd_m2", "roi"})
        EXPECT_TRUE(j.contains(k)) << k;
    // At least the noisiest 1 % of the pixels' own share, at most all of it.
    EXPECT_GE(j["noise_top1_share"].get<double>(), 0.01 - 1e-12);
    EXPECT_LE(j["noise_top1_share"].get<double>(), 1.0);
    // The camera pass says what it did (balanced by default).
    EXPECT_EQ(j["camera_pass"]["mode"], "balanced");
    for (const char* k : {"floor_samples", "samples", "samples_next_batch", "max_samples_per_pixel",
                          "pixels_above_floor", "device_time_share", "error_share"})
        EXPECT_TRUE(j["camera_pass"].contains(k)) << k;
    EXPECT_GE(j["camera_samples_per_pixel"].get<double>(), 16.0);  // at least one a batch
    // --reference: the image against itself has zero error.
    const CliRun r2 = run("render " + scene + " --out " + dir + "/again.exr --paths 200000 --width 40 "
                          "--no-progress --reference " + dir + "/new/out.exr --roi 5,5,30,25");
    ASSERT_EQ(r2.status, 0) << r2.err;
    const auto j2 = nlohmann::json::parse(slurp(dir + "/again.json"));
    EXPECT_EQ(j2["rmse_cd_m2"].get<double>(), 0.0);
    EXPECT_EQ(j2["rel_mse"].get<double>(), 0.0);
}

TEST(CliRender, NamedRegionsAreReportedLikeTheRoi)
{
    const std::string dir = test::tempDir("cli-render-regions");
    const std::string scene = plateScene().write(dir + "/plate.gltf");
    const std::string base = "render " + scene + " --out " + dir + "/r.exr --paths 200000 --width 40 --no-progress ";
    const CliRun r = run(base + "--roi 5,5,30,25 --region same=5,5,30,25 --region all=0,0,40,30");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(slurp(dir + "/r.json"));
    // A region equal to the ROI reports exactly the ROI's statistics.
    const auto& same = j["regions"]["same"];
    EXPECT_EQ(same["mean_luminance_cd_m2"], j["mean_luminance_cd_m2"]);
    EXPECT_EQ(same["mean_std_err_cd_m2"], j["mean_std_err_cd_m2"]);
    EXPECT_EQ(same["noise_std_err_cd_m2"], j["noise_std_err_cd_m2"]);
    EXPECT_EQ(j["regions"]["all"]["roi"], nlohmann::json({0, 0, 40, 30}));
    EXPECT_NE(j["regions"]["all"]["mean_luminance_cd_m2"], j["mean_luminance_cd_m2"]);
    expectError(run(base + "--region desk=0,0,50,10"), 1, "--region desk");
    expectError(run(base + "--region a=0,0,4,4 --region a=1,1,5,5"), 1, "--region a: given twice");
    expectError(run(base + "--region 0,0,4,4"), 1, "expected NAME=x0,y0,x1,y1");
}

TEST(CliRender, AFullDiskLosesNothing)
{
    // A write that fails (FEN_FAIL_WRITE injects ENOSPC into the outputs whose name holds it)
    // fails the render with one line naming the file, and leaves the previous render's outputs
    // whole and no temporaries behind.
    namespace fs = std::filesystem;
    const std::string dir = test::tempDir("cli-render-full-disk");
    const std::string scene = plateScene().write(dir + "/plate.gltf");
    const std::string args = "render " + scene + " --out " + dir + "/out/r.exr --paths 200000 --width 40 --no-progress";
    ASSERT_EQ(run(args).status, 0);
    const std::vector<std::string> files = {"/out/r.exr", "/out/r.noise.exr", "/out/r.png", "/out/r.json"};
    std::vector<std::string> before;
    for (const auto& f : files)
        before.push_back(slurp(dir + f));
    for (const char* failing : {"r.exr", "r.noise.exr", "r.png", "r.json"}) {
        expectError(run(args + " --seed 2", std::string("FEN_FAIL_WRITE=") + failing), 1, failing);
        for (std::size_t k = 0; k < files.size(); ++k)
            EXPECT_EQ(slurp(dir + files[k]), before[k]) << files[k] << " changed when " << failing << " failed";
        std::size_t entries = 0;
        for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir + "/out"))
            ++entries;
        EXPECT_EQ(entries, files.size()) << "a temporary was left behind when " << failing << " failed";
    }
    // Without the fault the same render replaces them.
    ASSERT_EQ(run(args + " --seed 2").status, 0);
    EXPECT_NE(slurp(dir + "/out/r.exr"), before[0]);
    // An output folder that cannot exist is refused before any rendering.
    expectError(run("render " + scene + " --out " + scene + "/x.exr --paths 200000 --no-progress"), 1, scene);
}

TEST(CliRender, AnInterruptedRenderWritesWhatItHas)
{
    // SIGTERM (like Ctrl-C's SIGINT) lets the batch in flight finish, then writes a valid image
    // of the batches done, says so in the JSON, and exits 130. 1024 batches of ~1M paths on a
    // plate take minutes, so the signal, 4 s in, arrives mid-render.
    const std::string dir = test::tempDir("cli-render-interrupt");
    const std::string scene = plateScene().write(dir + "/plate.gltf");
    const std::string cmd = std::string(FENESTRA_BIN) + " render " + scene + " --out " + dir +
                            "/r.exr --paths 1073741824 --batches 1024 --width 40 --no-progress 2>" + dir +
                            "/err & pid=$!; sleep 4; kill -TERM $pid; wait $pid; echo $? >" + dir + "/status";
    ASSERT_EQ(std::system(("bash -c '" + cmd + "'").c_str()), 0);
    EXPECT_EQ(std::stoi(slurp(dir + "/status")), 130) << slurp(dir + "/err");
    EXPECT_NE(slurp(dir + "/err").find("fenestra: interrupted"), std::string::npos) << slurp(dir + "/err");
    const auto j = nlohmann::json::parse(slurp(dir + "/r.json"));
    EXPECT_TRUE(j["interrupted"].get<bool>());
    const int batches = j["batches"];
    EXPECT_GE(batches, 1);
    EXPECT_LT(batches, 1024);
    EXPECT_EQ(j["paths"].get<std::uint64_t>(), j["paths_per_batch"].get<std::uint64_t>() * batches);
    EXPECT_EQ(j["last_batch_paths"], j["paths_per_batch"]);  // by paths: no last batch fitted to a clock
    EXPECT_GT(j["mean_luminance_cd_m2"].get<double>(), 0.0);
    EXPECT_EQ(j["counters"]["bad_contributions"], 0);
}

TEST(CliRender, ACheckpointResumesBitIdentically)
{
    // A render stopped by SIGTERM saves a checkpoint; --resume finishes it, and the EXR is the
    // byte-for-byte EXR of the render that was never stopped. A checkpoint of another render is
    // refused in one line. The stop comes 1 s in, so the render must last several seconds on
    // any device: 2^24 paths do on PoCL, a GPU needs hundreds of times more (measured first).
    const std::string dir = test::tempDir("cli-render-checkpoint");
    const std::string scene = plateScene().write(dir + "/plate.gltf");
    const CliRun probe = run("render " + scene + " --out " + dir + "/probe.exr --paths 4194304 --batches 16 "
                             "--width 40 --no-progress");
    ASSERT_EQ(probe.status, 0) << probe.err;
    const double pathsPerSecond = nlohmann::json::parse(slurp(dir + "/probe.json"))["paths_per_second"];
    std::uint64_t paths = 1u << 24;
    while (paths < 4.0 * pathsPerSecond)
        paths *= 2;
    // with a work plane: its cells are part of the state a checkpoint keeps
    const std::string args = " --paths " + std::to_string(paths) +
                             " --batches 256 --width 40 --seed 5 --no-progress --work-plane plate";
    ASSERT_EQ(run("render " + scene + " --out " + dir + "/whole.exr" + args).status, 0);
    const std::string cmd = std::string(FENESTRA_BIN) + " render " + scene + " --out " + dir + "/r.exr" + args +
                            " --checkpoint " + dir + "/c.ckpt 2>" + dir + "/err & pid=$!; sleep 1; kill -TERM $pid; "
                            "wait $pid; echo $? >" + dir + "/status";
    ASSERT_EQ(std::system(("bash -c '" + cmd + "'").c_str()), 0);
    ASSERT_EQ(std::stoi(slurp(dir + "/status")), 130) << slurp(dir + "/err");
    const CliRun r = run("render " + scene + " --out " + dir + "/r.exr" + args + " --resume " + dir + "/c.ckpt");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(slurp(dir + "/r.exr"), slurp(dir + "/whole.exr"));
    EXPECT_EQ(slurp(dir + "/r.sensors.csv"), slurp(dir + "/whole.sensors.csv"));
    EXPECT_FALSE(slurp(dir + "/r.sensors.csv").empty());
    const auto j = nlohmann::json::parse(slurp(dir + "/r.json"));
    EXPECT_GT(j["checkpoint"]["resumed_batches"].get<int>(), 0);
    EXPECT_EQ(j["progress"].size(), 256u);  // the records from before the stop came back
    expectError(run("render " + scene + " --out " + dir + "/x.exr" + args + " --resume " + dir +
                    "/c.ckpt --max-bounces 5"),
                1, "max_bounces was 1024, not 5");
    expectError(run("render " + scene + " --out " + dir + "/x.exr" + args + " --resume " + dir + "/none.ckpt"), 1,
                "none.ckpt");
    expectError(run("render " + scene + " --out " + dir + "/x.exr" + args + " --checkpoint-every 3parsecs"), 1,
                "--checkpoint-every");
}

// Where roulette starts is the method's default unless given (docs/results/termination.md):
// uniform emission's paths start outside and bounce there first, so they get two more free hits.
TEST(CliRender, RouletteStartsAtTheMethodsDefaultUnlessGiven)
{
    const std::string dir = test::tempDir("cli-render-roulette");
    const std::string scene = std::string(FEN_SCENES_DIR) + "/room.gltf";
    const auto depth = [&](const std::string& name, const std::string& opts) {
        const CliRun r = run("render " + scene + " --out " + dir + "/" + name + ".exr --paths 20000 "
                             "--width 16 --no-progress " + opts);
        EXPECT_EQ(r.status, 0) << r.err;
        return nlohmann::json::parse(slurp(dir + "/" + name + ".json"))["roulette_depth"].get<int>();
    };
    EXPECT_EQ(depth("u", "--method uniform"), 5);
    EXPECT_EQ(depth("p", "--method portal"), 3);
    EXPECT_EQ(depth("a", "--method adaptive"), 3);
    EXPECT_EQ(depth("u0", "--method uniform --roulette-depth 0"), 0);
    EXPECT_EQ(depth("p7", "--method portal --roulette-depth 7"), 7);
}

TEST(CliRender, TimeBudgetAndPortalsFromTheCommandLine)
{
    const std::string dir = test::tempDir("cli-render-time");
    // --time: a calibration, then at least two equal batches within about the budget, and perhaps a
    // last one fitted to the time left (render/last_batch.h): a quarter of a batch or more
    const CliRun t = run("render " + std::string(FEN_SCENES_DIR) + "/room.gltf --out " + dir +
                         "/t.exr --time 3 --width 64 --no-progress");
    ASSERT_EQ(t.status, 0) << t.err;
    const auto jt = nlohmann::json::parse(slurp(dir + "/t.json"));
    EXPECT_GE(jt["batches"].get<int>(), 2);
    EXPECT_LT(jt["seconds"]["render"].get<double>() + jt["seconds"]["calibration"].get<double>(), 4.5);
    const std::uint64_t perBatch = jt["paths_per_batch"], last = jt["last_batch_paths"];
    EXPECT_EQ(jt["paths"].get<std::uint64_t>(), perBatch * (jt["batches"].get<std::uint64_t>() - 1) + last);
    EXPECT_LE(last, perBatch);
    EXPECT_GE(4 * last, perBatch);
    // portals: the scene's marking (window + door frame) and an override
    const CliRun p = run("render " + std::string(FEN_SCENES_DIR) + "/inner_room.gltf --out " + dir +
                         "/p.exr --method portal --paths 100000 --width 64 --no-progress");
    ASSERT_EQ(p.status, 0) << p.err;
    const auto jp = nlohmann::json::parse(slurp(dir + "/p.json"));
    EXPECT_EQ(jp["method"], "portal");
    EXPECT_EQ(jp["emission"]["portal_nodes"], nlohmann::json({"window", "door_frame"}));
    EXPECT_GT(jp["emission"]["sun_flux_lm"].get<double>(), 0.0);
    const CliRun g = run("render " + std::string(FEN_SCENES_DIR) + "/inner_room.gltf --out " + dir +
                         "/g.exr --method portal --portals gap --paths 100000 --width 64 --no-progress");
    ASSERT_EQ(g.status, 0) << g.err;
    EXPECT_EQ(nlohmann::json::parse(slurp(dir + "/g.json"))["emission"]["portal_nodes"],
              nlohmann::json({"gap"}));
}

TEST(CliRender, BadInputIsOneLineNamingTheProblem)
{
    const std::string dir = test::tempDir("cli-render-bad");
    const std::string out = " --out " + dir + "/o.exr --paths 1000 --no-progress";
    auto variant = [&](const std::string& name, auto edit) {
        test::GltfWriter w = plateScene();
        edit(w);
        return w.write(dir + "/" + name + ".gltf");
    };
    expectError(run("render /no/such.gltf" + out), 1, "/no/such.gltf");
    const std::string noCam = variant("nocam", [](test::GltfWriter& w) {
        w.doc()["scenes"][0]["nodes"] = {0};
    });
    expectError(run("render " + noCam + out), 1, "no camera");
    const std::string neg = variant("neg", [](test::GltfWriter& w) {
        w.doc()["scenes"][0]["extras"]["sky"]["luminance"] = -5;
    });
    expectError(run("render " + neg + out), 1, "extras.sky.luminance");
    const std::string unknownType = variant("type", [](test::GltfWriter& w) {
        w.doc()["scenes"][0]["extras"]["sky"] = {{"type", "sunset"}};
    });
    expectError(run("render " + unknownType + out), 1, "'sunset'");
    const std::string unknownKey = variant("key", [](test::GltfWriter& w) {
        w.doc()["scenes"][0]["extras"]["sky"]["brightness"] = 3;
    });
    expectError(run("render " + unknownKey + out), 1, "extras.sky.brightness: unknown key");
    const std::string badCie = variant("cie", [](test::GltfWriter& w) {
        w.doc()["scenes"][0]["extras"]["sky"] = {{"type", "cie"}, {"cie_type", 16}, {"zenith_luminance", 1},
                                                 {"sun_altitude_deg", 30}, {"sun_azimuth_deg", 0}};
    });
    expectError(run("render " + badCie + out), 1, "cie_type");
    const std::string lines = variant("lines", [](test::GltfWriter& w) {
        w.doc()["meshes"][0]["primitives"][0]["mode"] = 1;
    });
    expectError(run("render " + lines + out), 1, "mode 1");
    const std::string point = variant("point", [](test::GltfWriter& w) {
        w.doc()["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}, {"intensity", 5}}};
        w.doc()["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 0;
    });
    expectError(run("render " + point + out), 1, "'point' lights");
    const std::string good = plateScene().write(dir + "/good.gltf");
    expectError(run("render " + good + " --out " + dir + "/o.png --paths 10"), 1, "--out");
    expectError(run("render " + good + out + " --camera nope"), 1, "'nope'");
    expectError(run("render " + good + out + " --roi 1,2,3"), 1, "--roi");
    expectError(run("render " + good + out + " --roi 0,0,999,10"), 1, "--roi");
    expectError(run("render " + good + out + " --time 5"), 1, "either --paths or --time");
    expectError(run("render " + good + " --out " + dir + "/o.exr --no-progress --reference /no/ref.exr --paths 10"),
                1, "/no/ref.exr");
    expectError(run("render " + good + out + " --width -3"), 1, "--width");
    expectError(run("render " + good + out + " --camera-spp 5000"), 1, "--camera-spp");
    const std::string upward = variant("upward", [](test::GltfWriter& w) {
        w.doc()["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "directional"}, {"intensity", 5}}};
        w.doc()["nodes"].push_back({{"name", "sun"}, {"rotation", {0.7071067811865476, 0, 0, 0.7071067811865476}},
                                   {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
        w.doc()["scenes"][0]["nodes"].push_back(w.doc()["nodes"].size() - 1);
    });
    expectError(run("render " + upward + out), 1, "below the horizon");
    const std::string huge = variant("huge", [](test::GltfWriter& w) {
        w.doc()["scenes"][0]["extras"]["sky"]["luminance"] = 1e35;
    });
    expectError(run("render " + huge + out), 1, "extras.sky.luminance");
    expectError(run("render " + good + out + " --method sideways"), 1, "--method");
    expectError(run("render " + good + out + " --method portal"), 1, "no portals");
    expectError(run("render " + good + out + " --method portal --portals nope"), 1, "'nope'");
    expectError(run("render " + good + out + " --portals plate"), 1, "--method portal");
    expectError(run("render " + good + out + " --method uniform --portals plate"), 1, "--base portal");
    expectError(run("render " + good + out + " --method portal --portal-overlap maybe"), 1, "--portal-overlap");
    expectError(run("render " + good + " --out /proc/no/such/o.exr --paths 10 --no-progress"), 1, "/proc/no/such");
}

TEST(CliRender, AdaptiveReportsItsGrid)
{
    const std::string dir = test::tempDir("cli-render-adaptive");
    for (const char* base : {"uniform", "portal"}) {
        const std::string out = dir + "/a_" + base + ".exr";
        const CliRun r = run("render " + std::string(FEN_SCENES_DIR) + "/inner_room.gltf --out " + out +
                             " --method adaptive --base " + base + " --paths 300000 --width 64 --no-progress");
        ASSERT_EQ(r.status, 0) << r.err;
        const auto j = nlohmann::json::parse(slurp(dir + "/a_" + base + ".json"));
        EXPECT_EQ(j["method"], "adaptive");
        const auto& e = j["emission"];
        EXPECT_EQ(e["base"], base);
        for (const char* k : {"cells", "max_cells", "memory_bytes", "passes", "deepest", "deepest_sky", "defensive",
                              "estimate", "batch_weights", "checksum", "probability", "learn_seconds"})
            EXPECT_TRUE(e.contains(k)) << k;
        EXPECT_GT(e["memory_bytes"].get<std::uint64_t>(), 0u);
        EXPECT_EQ(e["batch_weights"].size(), j["batches"].get<std::size_t>());
        EXPECT_EQ(j["counters"]["stats_overflows"], 0);
        if (std::string(base) == "portal") {
            EXPECT_EQ(e["portal_nodes"], nlohmann::json({"window", "door_frame"}));
        }
        EXPECT_EQ(e["target"], "absolute");
        // weight windows, rule moment, splitting only, by default (DESIGN.md §3.4)
        EXPECT_EQ(e["guide"]["window"], "moment");
        EXPECT_EQ(e["guide"]["window_min_survival"], 1.0);
        // every slot that has seen enough steers (docs/results/guiding.md)
        EXPECT_EQ(e["guide"]["min_gain"], 1.0);
    }
    // The relative target is what it says, and as deterministic as the absolute one: the same
    // image whatever the pool size, though its statistics follow the image estimate pass by pass.
    std::string bytes[2];
    for (int k = 0; k < 2; ++k) {
        const std::string out = dir + "/relative_" + std::to_string(k) + ".exr";
        const CliRun r = run("render " + std::string(FEN_SCENES_DIR) + "/room.gltf --out " + out +
                             " --adaptive-target relative --paths 1048576 --width 64 --no-progress --pool " +
                             (k == 0 ? "65536" : "8192"));
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_EQ(nlohmann::json::parse(slurp(dir + "/relative_" + std::to_string(k) + ".json"))["emission"]["target"],
                  "relative");
        bytes[k] = slurp(out);
    }
    EXPECT_FALSE(bytes[0].empty());
    EXPECT_EQ(bytes[0], bytes[1]);
}

TEST(CliRender, PortalsWarnAboutTheLightTheyMiss)
{
    // scenes/room.gltf: the sunlit ground outside sends light in through the window that no path
    // starting on the window carries; the complement paths measure it and the render says so.
    const std::string dir = test::tempDir("cli-render-unreached");
    const CliRun r = run("render " + std::string(FEN_SCENES_DIR) + "/room.gltf --out " + dir +
                         "/p.exr --method portal --paths 3000000 --width 64 --no-progress");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("does not pass through the marked portals"), std::string::npos) << r.err;
    const auto j = nlohmann::json::parse(slurp(dir + "/p.json"));
    EXPECT_GT(j["emission"]["unreached"]["share"].get<double>(), 0.01);
    // --portal-complement 0: the paper's method alone, nothing measured, no warning.
    const CliRun q = run("render " + std::string(FEN_SCENES_DIR) + "/room.gltf --out " + dir +
                         "/q.exr --method portal --portal-complement 0 --paths 300000 --width 64 --no-progress");
    ASSERT_EQ(q.status, 0) << q.err;
    EXPECT_EQ(q.err.find("warning"), std::string::npos) << q.err;
    EXPECT_TRUE(nlohmann::json::parse(slurp(dir + "/q.json"))["emission"]["unreached"].is_null());
}

TEST(CliCompare, ChartsAndTableFromEqualTimeRenders)
{
    // scripts/compare.py: equal-time renders against a reference, CSV, summary and charts (the
    // install step of matplotlib is scripts/setup.sh's).
    const std::string dir = test::tempDir("cli-compare");
    const std::string scene = std::string(FEN_SCENES_DIR) + "/room.gltf";
    const std::string cmd = "cd " + std::string(FEN_SOURCE_DIR) + " && /usr/bin/python3 scripts/compare.py " + scene +
                            " --methods uniform,portal,adaptive --time 1.5 --reference-time 3 --width 48 --out " + dir +
                            " --fenestra " + FENESTRA_BIN + " > " + dir + "/log 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(dir + "/log");
    for (const char* f : {"/compare.csv", "/summary.md", "/summary.json", "/error_vs_time.png", "/efficiency.png",
                          "/strip.png", "/adaptive.error.png"})
        EXPECT_FALSE(slurp(dir + f).empty()) << f;
    const auto j = nlohmann::json::parse(slurp(dir + "/summary.json"));
    ASSERT_EQ(j["methods"].size(), 3u);
    for (const auto& m : j["methods"])
        for (const char* k : {"method", "paths", "mean_cd_m2", "bias_cd_m2", "biased", "rmse_cd_m2", "relative_efficiency"})
            EXPECT_TRUE(m.contains(k)) << k;
    EXPECT_NE(slurp(dir + "/compare.csv").find("method,batches,paths,seconds"), std::string::npos);
}

// The openings' walks (--adaptive-openings-share, DESIGN.md §3.6) with a work plane: the floor's
// mean illuminance within 4 sigma of adaptive without them (the walks' paths teach no emission
// cell and the sensors take their flux as any light path's), and the JSON counts the walks. The
// default, auto, at 2e6 paths has no pass of 2^22 to race (its batches cut every pass shorter): it
// renders without walks, and says so: ready, the aim listing panes, but not raced.
TEST(CliRender, OpeningWalksKeepTheWorkPlanesIlluminance)
{
    const std::string dir = test::tempDir("cli-render-opening-walks");
    const std::string render = "render " + std::string(FEN_SCENES_DIR) +
                               "/courtyard.gltf --work-plane floor --sensor-spacing 0.5 --paths 2000000 --width 32 "
                               "--no-progress --out " + dir;
    const CliRun without = run(render + "/without.exr");
    ASSERT_EQ(without.status, 0) << without.err;
    const CliRun with = run(render + "/with.exr --adaptive-openings-share 0.9");
    ASSERT_EQ(with.status, 0) << with.err;
    const auto a = nlohmann::json::parse(slurp(dir + "/without.json"));
    const auto b = nlohmann::json::parse(slurp(dir + "/with.json"));
    const auto& pa = a["sensors"]["workplane"];
    const auto& pb = b["sensors"]["workplane"];
    const double ma = pa["mean_lux"].get<double>(), mb = pb["mean_lux"].get<double>();
    const double sa = pa["mean_lux_std_err"].get<double>(), sb = pb["mean_lux_std_err"].get<double>();
    EXPECT_LT(std::abs(ma - mb), 4.0 * std::sqrt(sa * sa + sb * sb)) << ma << " +- " << sa << " against " << mb
                                                                      << " +- " << sb;
    EXPECT_GT(mb, 0.0);
    EXPECT_EQ(a["counters"]["opening_walks"].get<double>(), 0.0);
    EXPECT_EQ(a["emission"]["openings_share_auto"], true);
    EXPECT_EQ(a["emission"]["openings_race"]["phase"], "ready");
    EXPECT_GT(b["counters"]["opening_walks"].get<double>(), 1e6);
    EXPECT_EQ(b["emission"]["openings_share_auto"], false);
    EXPECT_DOUBLE_EQ(b["emission"]["openings_share"].get<double>(), 0.9);
    // with sensors alone the aim learns nothing to start the walks from: said, not silently ignored
    expectError(run("render " + std::string(FEN_SCENES_DIR) + "/courtyard.gltf --work-plane floor --no-image "
                    "--paths 1000 --no-progress --adaptive-openings-share 0.9 --out " + dir + "/s"),
                1, "--adaptive-openings-share: needs an image (the walks start on the panes the opening aim learns from "
                   "what reaches the camera), and --no-image renders none");
}

TEST(CliRender, AdaptiveBadOptionsAreOneLine)
{
    const std::string dir = test::tempDir("cli-render-adaptive-bad");
    const std::string good = plateScene().write(dir + "/good.gltf");
    const std::string out = " --out " + dir + "/o.exr --paths 1000 --no-progress";
    expectError(run("render " + good + out + " --method adaptive --base portal"), 1, "no portals");
    expectError(run("render " + good + out + " --method adaptive --base sideways"), 1, "--method 'sideways'");
    expectError(run("render " + good + out + " --method adaptive --base adaptive"), 1, "--base");
    expectError(run("render " + good + out + " --method uniform --base portal"), 1, "--base applies to --method adaptive");
    expectError(run("render " + good + out + " --method uniform --adaptive-max-depth 4"), 1, "--method adaptive");
    expectError(run("render " + good + out + " --method portal --portals plate --adaptive-target relative"), 1,
                "--method adaptive");
    expectError(run("render " + good + out + " --adaptive-target sideways"), 1, "--adaptive-target 'sideways'");
    // adaptive is the default method: --base alone applies
    expectError(run("render " + good + out + " --base portal"), 1, "no portals");
    expectError(run("render " + good + out + " --method adaptive --adaptive-max-depth 17"), 1, "--adaptive-max-depth 17");
    expectError(run("render " + good + out + " --method adaptive --adaptive-initial-depth 5 --adaptive-max-depth 3"), 1,
                "--adaptive-initial-depth 5");
    expectError(run("render " + good + out + " --method adaptive --adaptive-max-sky-depth 13"), 1,
                "--adaptive-max-sky-depth");
    expectError(run("render " + good + out + " --method adaptive --adaptive-defensive 0"), 1, "--adaptive-defensive");
    expectError(run("render " + good + out + " --method adaptive --adaptive-defensive 1.5"), 1, "--adaptive-defensive");
    expectError(run("render " + good + out + " --method adaptive --base portal --portals plate --adaptive-disk-share 1"),
                1, "--adaptive-disk-share");
    expectError(run("render " + good + out + " --method adaptive --adaptive-first-pass 10"), 1, "--adaptive-first-pass");
    expectError(run("render " + good + out + " --method adaptive --adaptive-split 0"), 1, "--adaptive-split");
    expectError(run("render " + good + out + " --method adaptive --adaptive-estimate median"), 1,
                "--adaptive-estimate 'median': expected larger, pooled or squares");
    expectError(run("render " + good + out + " --method adaptive --adaptive-max-cells 8"), 1, "--adaptive-max-cells 8");
    // the first-bounce guide: on or off, a share that keeps every direction drawable, a sane lattice
    expectError(run("render " + good + out + " --adaptive-guide maybe"), 1, "--adaptive-guide 'maybe'");
    expectError(run("render " + good + out + " --method uniform --adaptive-guide on"), 1, "--method adaptive");
    expectError(run("render " + good + out + " --adaptive-guide on --adaptive-guide-share 0"), 1,
                "--adaptive-guide-share 0");
    expectError(run("render " + good + out + " --adaptive-guide on --adaptive-guide-voxels 0"), 1,
                "--adaptive-guide-voxels 0");
    // ... its trees: a depth from the fixed 8 x 8 to the finest, positive split thresholds, a memory
    // that holds the starting trees
    expectError(run("render " + good + out + " --adaptive-guide-depth 2"), 1, "--adaptive-guide-depth 2");
    expectError(run("render " + good + out + " --adaptive-guide-depth 13"), 1, "--adaptive-guide-depth 13");
    expectError(run("render " + good + out + " --adaptive-guide-split 0"), 1, "--adaptive-guide-split 0");
    expectError(run("render " + good + out + " --adaptive-guide-space-split 0"), 1,
                "--adaptive-guide-space-split 0");
    expectError(run("render " + good + out + " --adaptive-guide-memory 1"), 1, "--adaptive-guide-memory 1");
    // ... and the gate is a cut of the second moment, at least 1: below, a table promising more variance would steer
    expectError(run("render " + good + out + " --adaptive-guide-min-gain 0.5"), 1, "--adaptive-guide-min-gain 0.5");
    expectError(run("render " + good + out + " --method uniform --adaptive-guide-min-gain 2"), 1, "--method adaptive");
    expectError(run("render " + good + out + " --adaptive-guide-min-contributions 0"), 1,
                "--adaptive-guide-min-contributions 0");
    expectError(run("render " + good + out + " --adaptive-guide-voxels 17"), 1, "--adaptive-guide-voxels 17");
    // more voxels than the default memory holds: the message names the voxels and the memory they need
    expectError(run("render " + good + out + " --adaptive-guide-voxels 16"), 1,
                "--adaptive-guide-voxels 16: needs --adaptive-guide-memory 1413 or more");
    expectError(run("render " + good + out + " --adaptive-guide-vertices all"), 1, "--adaptive-guide-vertices 'all'");
    // weight windows: a rule, at least two branches, a survival that is not 0, only with the guide
    expectError(run("render " + good + out + " --adaptive-window on"), 1, "--adaptive-window 'on'");
    expectError(run("render " + good + out + " --adaptive-window mean --adaptive-window-split 1"), 1,
                "--adaptive-window-split 1");
    // a branch's number is a byte of its random numbers' key: 256 branches would repeat branch 0
    expectError(run("render " + good + out + " --adaptive-window-split 256"), 1,
                "--adaptive-window-split 256: must be in 2..255");
    expectError(run("render " + good + out + " --adaptive-window moment --adaptive-window-survival 0"), 1,
                "--adaptive-window-survival 0");
    expectError(run("render " + good + out + " --adaptive-window off --adaptive-window-split 8"), 1,
                "--adaptive-window-split: applies with weight windows, which --adaptive-window off turns off");
    expectError(run("render " + good + out + " --adaptive-guide off --adaptive-window-survival 0.5"), 1,
                "--adaptive-window-survival: applies with weight windows, which --adaptive-guide off turns off");
    expectError(run("render " + good + out + " --adaptive-window mean --adaptive-guide off"), 1,
                "--adaptive-window: needs");
    expectError(run("render " + good + out + " --adaptive-window-vertices all"), 1,
                "--adaptive-window-vertices 'all': expected every or first");
    expectError(run("render " + good + out + " --adaptive-window off --adaptive-window-vertices first"), 1,
                "--adaptive-window-vertices: applies with weight windows, which --adaptive-window off turns off");
    // lower windows past the first vertex: a factor from 1 (the first vertex's) up, only where paths split there
    expectError(run("render " + good + out + " --adaptive-window-later 0.5"), 1,
                "--adaptive-window-later 0.5: must be in [1, 64]");
    expectError(run("render " + good + out + " --adaptive-window-later 65"), 1, "--adaptive-window-later 65");
    expectError(run("render " + good + out + " --adaptive-window-vertices first --adaptive-window-later 2"), 1,
                "--adaptive-window-later: applies past the first vertex, which --adaptive-window-vertices first turns off");
    expectError(run("render " + good + out + " --adaptive-window off --adaptive-window-later 2"), 1,
                "--adaptive-window-later: applies with weight windows, which --adaptive-window off turns off");
    // the opening aim's share: learned or a number; its bounds in range, only when it is learned
    expectError(run("render " + good + out + " --adaptive-aim-share maybe"), 1,
                "--adaptive-aim-share 'maybe': expected learned or a number in (0, 1)");
    expectError(run("render " + good + out + " --adaptive-aim-share 0.5x"), 1,
                "--adaptive-aim-share '0.5x': expected learned or a number in (0, 1)");
    expectError(run("render " + good + out + " --adaptive-aim-share 1"), 1, "--adaptive-aim-share 1: must be in (0, 1)");
    expectError(run("render " + good + out + " --adaptive-aim off --adaptive-aim-share learned"), 1,
                "--adaptive-aim-share: applies with the opening aim, which --adaptive-aim off turns off");
    expectError(run("render " + good + out + " --adaptive-aim-share 0.5 --adaptive-aim-share-min 0.3"), 1,
                "--adaptive-aim-share-min: applies with --adaptive-aim-share learned (the share is fixed otherwise)");
    expectError(run("render " + good + out + " --adaptive-aim-share-max 0.9"), 1,
                "--adaptive-aim-share-max: applies with --adaptive-aim-share learned (the share is fixed otherwise)");
    expectError(run("render " + good + out + " --adaptive-window off --adaptive-aim-share learned"), 1,
                "--adaptive-aim-share learned: the share is learned from the weight windows' sums, which --adaptive-window off turns off");
    expectError(run("render " + good + out + " --adaptive-aim-share learned --adaptive-aim-share-min 0"), 1,
                "--adaptive-aim-share-min 0: must be in (0, 1)");
    expectError(run("render " + good + out + " --adaptive-aim-share learned --adaptive-aim-share-max 0.2"), 1,
                "--adaptive-aim-share-max 0.2: must be in [0.25, 1]");
    // the openings' walks: a share in [0, 1), adaptive with its aim only
    expectError(run("render " + good + out + " --adaptive-openings-share 1"), 1,
                "--adaptive-openings-share 1: must be in [0, 1) (the light paths keep the light the walks cannot take)");
    expectError(run("render " + good + out + " --adaptive-openings-share -0.1"), 1, "--adaptive-openings-share -0.1: must be in [0, 1)");
    expectError(run("render " + good + out + " --adaptive-openings-share half"), 1,
                "--adaptive-openings-share 'half': expected auto or a number in [0, 1)");
    // ... or auto (the default), raced in passes of 2^16 paths or more
    expectError(run("render " + good + out + " --adaptive-openings-share 0.5 --adaptive-openings-race-paths 4194304"), 1,
                "--adaptive-openings-race-paths: applies with --adaptive-openings-share auto");
    expectError(run("render " + good + out + " --adaptive-aim off --adaptive-openings-race-paths 4194304"), 1,
                "--adaptive-openings-race-paths: applies with the opening aim, which --adaptive-aim off turns off");
    expectError(run("render " + good + out + " --adaptive-openings-share auto --adaptive-openings-race-paths 1000"), 1,
                "--adaptive-openings-race-paths 1000: must be in 65536..2^40 paths");
    expectError(run("render " + good + out + " --adaptive-aim off --adaptive-openings-share 0.9"), 1,
                "--adaptive-openings-share: applies with the opening aim, which --adaptive-aim off turns off");
    expectError(run("render " + good + out + " --method uniform --adaptive-openings-share 0.9"), 1,
                "the --adaptive-* options apply to --method adaptive");
    // splitting: a count of branches, a positive weight unit -- never silently the default
    expectError(run("render " + good + out + " --split 0"), 1, "--split 0");
    expectError(run("render " + good + out + " --split -1"), 1, "--split -1");
    expectError(run("render " + good + out + " --split 256"), 1, "--split 256");
    expectError(run("render " + good + out + " --split 4 --split-weight 0"), 1, "--split-weight 0");
    expectError(run("render " + good + out + " --split 4 --split-weight -3"), 1, "--split-weight -3");
}

// Scenes from other people (README, "Untrusted scenes"): one line naming the file and the glTF
// path, exit status 1, never a crash, never a byte or the size of another file.
std::string untrustedOut(const std::string& dir) { return " --out " + dir + "/o.exr --paths 1000 --no-progress"; }

TEST(CliUntrusted, BufferUriOutsideTheSceneFolder)
{
    const std::string dir = test::tempDir("cli-untrusted-uri");
    std::ofstream(dir + "/secret.txt") << std::string(1221, 's');
    std::filesystem::create_directories(dir + "/scene");
    test::GltfWriter w = plateScene();
    w.writeExternal(dir + "/scene/s.gltf", "plate.bin", "..%2Fsecret.txt");
    const CliRun r = run("render " + dir + "/scene/s.gltf" + untrustedOut(dir));
    expectError(r, 1, "s.gltf: buffers[0].uri: '..%2Fsecret.txt' leads outside the scene's folder");
    EXPECT_EQ(r.err.find("1221"), std::string::npos) << r.err;
}

TEST(CliUntrusted, OffsetNear2To64)
{
    const std::string dir = test::tempDir("cli-untrusted-wrap");
    test::GltfWriter w = plateScene();
    w.doc()["bufferViews"][0]["byteOffset"] = ~std::uint64_t(0) - 7;  // + byteLength wraps past 2^64
    expectError(run("render " + w.write(dir + "/wrap.gltf") + untrustedOut(dir)), 1,
                "wrap.gltf: node 0 'plate', mesh 0, primitive 0, accessor 0: bufferView 0");
}

TEST(CliUntrusted, DeepNestingAndDagsAreOneLineErrors)
{
    const std::string dir = test::tempDir("cli-untrusted-deep");
    test::GltfWriter w = plateScene();
    w.node(0)["extras"] = "PLACEHOLDER";
    const std::string path = w.write(dir + "/deep.gltf");
    std::string text = slurp(path), deep;
    for (int i = 0; i < 20000; ++i)
        deep += "{\"a\":";
    deep += "1" + std::string(20000, '}');
    text.replace(text.find("\"PLACEHOLDER\""), 13, deep);
    std::ofstream(path) << text;
    expectError(run("render " + path + untrustedOut(dir)), 1, "deep.gltf: JSON nested deeper than 64 levels");

    test::GltfWriter d = plateScene();
    int top = 0;  // each level lists the one below twice: 2^30 plates from a 6 KB file
    for (int i = 0; i < 30; ++i) {
        d.doc()["nodes"].push_back({{"children", {top, top}}});
        top = static_cast<int>(d.doc()["nodes"].size()) - 1;
    }
    d.doc()["scenes"][0]["nodes"] = {1, top};
    expectError(run("render " + d.write(dir + "/dag.gltf") + untrustedOut(dir)), 1,
                "dag.gltf: nodes[2].children[1]: nodes[0] 'plate' is listed twice");
}

TEST(CliUntrusted, WideIntegersAreNotSqueezedInto32Bits)
{
    const std::string dir = test::tempDir("cli-untrusted-wide");
    const std::uint64_t k2To32 = std::uint64_t(1) << 32;
    test::GltfWriter w = plateScene();
    w.doc()["scenes"][0]["extras"]["sky"] = {{"type", "cie"}, {"cie_type", k2To32 + 12}, {"zenith_luminance", 1},
                                             {"sun_altitude_deg", 45}, {"sun_azimuth_deg", 0}};
    expectError(run("render " + w.write(dir + "/cie.gltf") + untrustedOut(dir)), 1,
                "cie.gltf: scenes[0].extras.sky.cie_type: 4294967308 is not a CIE sky type");
    test::GltfWriter m = plateScene();
    m.node(0)["mesh"] = k2To32;
    expectError(run("render " + m.write(dir + "/mesh.gltf") + untrustedOut(dir)), 1,
                "mesh.gltf: nodes[0].mesh: 4294967296 is not an index of meshes (1 of them)");
}

TEST(CliUntrusted, WrongShapesAreErrors)
{
    const std::string dir = test::tempDir("cli-untrusted-shape");
    test::GltfWriter t = plateScene();
    t.node(1)["translation"] = {0, 3};  // was ignored: the camera sat at the origin
    expectError(run("render " + t.write(dir + "/t.gltf") + untrustedOut(dir)), 1,
                "t.gltf: nodes[1].translation: must be an array of 3 numbers");
    test::GltfWriter c = plateScene();
    c.doc()["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.2, 0.2}}}}}};
    c.doc()["meshes"][0]["primitives"][0]["material"] = 0;  // was white
    expectError(run("render " + c.write(dir + "/c.gltf") + untrustedOut(dir)), 1,
                "c.gltf: materials[0].pbrMetallicRoughness.baseColorFactor: must be an array of 4 numbers");
}

TEST(CliUntrusted, FarGeometryIsAWarning)
{
    // A triangle a thousand kilometres away: the render goes on, with a word about it.
    const std::string dir = test::tempDir("cli-untrusted-far");
    test::GltfWriter w = plateScene();
    w.addMeshNode("speck", {{{1e6f, 0, 0}, {1e6f + 1, 0, 0}, {1e6f, 1, 0}}});
    const CliRun r = run("render " + w.write(dir + "/far.gltf") + " --out " + dir +
                         "/o.exr --paths 20000 --width 32 --no-progress");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("fenestra: warning: " + dir + "/far.gltf: node 2 'speck' makes the scene's bounding box"),
              std::string::npos) << r.err;
}


// scenes/blender_room.glb was built and written by Blender's own glTF exporter
// (scripts/blender_room.py); scenes/blender_room_twin.gltf is the same room written by hand. With
// the sky given on the command line (glTF cannot carry Blender's World), the two must render
// alike: the textured floor, a wall and the whole image within 4 standard errors of their
// difference (two independent seeds). Also: the Blender file brings its sun (75,000 lux from
// Strength 109.8 W/m^2), camera, glass and portal marking along, and nothing is warned about.
TEST(CliBlender, RendersAsItsHandWrittenTwin)
{
    const std::string dir = test::tempDir("cli-blender");
    const std::string common = " --sky cie:12 --sky-lux 20000 --paths 6000000 --width 160 --no-progress"
                               " --region floor=40,80,120,120 --region wall=0,0,40,60";
    const CliRun a = run("render " + std::string(FEN_SCENES_DIR) + "/blender_room.glb --out " + dir + "/a.exr --seed 1" + common);
    ASSERT_EQ(a.status, 0) << a.err;
    EXPECT_EQ(a.err.find("warning"), std::string::npos) << a.err;
    const CliRun b = run("render " + std::string(FEN_SCENES_DIR) + "/blender_room_twin.gltf --out " + dir + "/b.exr --seed 2" + common);
    ASSERT_EQ(b.status, 0) << b.err;
    const auto ja = nlohmann::json::parse(slurp(dir + "/a.json")), jb = nlohmann::json::parse(slurp(dir + "/b.json"));
    EXPECT_NEAR(ja["sun"]["normal_illuminance_lux"].get<double>(), 75000.0, 0.01);
    EXPECT_NEAR(ja["sun"]["altitude_deg"].get<double>(), 40.0, 1e-4);
    EXPECT_NEAR(ja["sun"]["azimuth_deg"].get<double>(), 170.0, 1e-4);
    const auto compare = [&](const nlohmann::json& x, const nlohmann::json& y, const char* what) {
        const double mx = x["mean_luminance_cd_m2"].get<double>(), my = y["mean_luminance_cd_m2"].get<double>();
        const double se = std::hypot(x["mean_std_err_cd_m2"].get<double>(), y["mean_std_err_cd_m2"].get<double>());
        std::printf("[ blender ] %s: %.2f vs twin %.2f, %+.2f sigma\n", what, mx, my, (mx - my) / se);
        EXPECT_NEAR(mx, my, 4.0 * se) << what;
        EXPECT_LT(se, 0.02 * my) << what << ": too noisy to compare";
    };
    compare(ja, jb, "image");
    compare(ja["regions"]["floor"], jb["regions"]["floor"], "textured floor");
    compare(ja["regions"]["wall"], jb["regions"]["wall"], "wall");
    // The portal marking came through: portal emission runs and finds the window.
    const CliRun p = run("render " + std::string(FEN_SCENES_DIR) + "/blender_room.glb --out " + dir +
                         "/p.exr --method portal --portal-complement 0 --sky cie:12 --sky-lux 20000 --paths 200000 --width 64 --no-progress");
    ASSERT_EQ(p.status, 0) << p.err;
    EXPECT_EQ(nlohmann::json::parse(slurp(dir + "/p.json"))["emission"]["portal_nodes"], nlohmann::json::array({"window"}));
}

TEST(CliBlender, WithoutASkyTheRenderSaysHowToGiveOne)
{
    const std::string dir = test::tempDir("cli-blender-nosky");
    const CliRun r = run("render " + std::string(FEN_SCENES_DIR) + "/blender_room.glb --out " + dir +
                         "/a.exr --paths 100000 --width 32 --no-progress");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("has no sky"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--sky cie:12 --sky-lux"), std::string::npos) << r.err;
    // A Blender user's 60,000 "W/m^2" sun arrives as 41 Mlux: warned, with the option that fixes it.
    std::string glb = slurp(std::string(FEN_SCENES_DIR) + "/blender_room.glb");
    const std::string from = "\"intensity\":74999.99905395508", to = "\"intensity\":40980000.00000000";
    ASSERT_EQ(from.size(), to.size());
    const std::size_t at = glb.find(from);
    ASSERT_NE(at, std::string::npos);
    glb.replace(at, from.size(), to);
    std::ofstream(dir + "/bright.glb", std::ios::binary) << glb;
    const CliRun q = run("render " + dir + "/bright.glb --out " + dir + "/b.exr --sky cie:12 --sky-lux 20000 "
                         "--paths 100000 --width 32 --no-progress");
    ASSERT_EQ(q.status, 0) << q.err;
    EXPECT_NE(q.err.find("exceeds any sun's on Earth"), std::string::npos) << q.err;
    const CliRun f = run("render " + dir + "/bright.glb --out " + dir + "/c.exr --sky cie:12 --sky-lux 20000 "
                         "--sun-lux 100000 --paths 100000 --width 32 --no-progress");
    ASSERT_EQ(f.status, 0) << f.err;
    EXPECT_EQ(f.err.find("warning"), std::string::npos) << f.err;
}

TEST(CliBlender, SkyAndSunOptionsAreOneLineErrors)
{
    const std::string scene = std::string(FEN_SCENES_DIR) + "/blender_room.glb";
    const std::string out = test::tempDir("cli-skysun") + "/x.exr";
    expectError(run("render " + scene + " --out " + out + " --paths 1000 --sky cie:12"), 1, "--sky cie:12 needs its brightness");
    expectError(run("render " + scene + " --out " + out + " --paths 1000 --sky cloudy --sky-lux 1"), 1, "--sky 'cloudy'");
    expectError(run("render " + scene + " --out " + out + " --paths 1000 --site 45,8 --sun-at 2026-06-21T14:00"), 1,
                "no UTC offset");
    expectError(run("render " + scene + " --out " + out + " --paths 1000 --sun 95,180"), 1, "--sun 95,180");
}

// A weather file's hour gives the sun and a Perez sky: the JSON says so, with the hour's numbers,
// and every way of asking wrongly is a one-line error naming the option, the file or the hour.
TEST(CliWeather, AnHourOfTheShippedYear)
{
    const std::string epw = std::string(FEN_SCENES_DIR) + "/weather/tmy_45.000_8.000_2005_2016.epw";
    const std::string scene = std::string(FEN_SCENES_DIR) + "/room.gltf";
    const std::string dir = test::tempDir("cli-weather");
    const CliRun r = run("render " + scene + " --out " + dir + "/w.exr --weather " + epw +
                         " --weather-hour 06-21:13 --paths 200000 --width 32 --no-progress");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(slurp(dir + "/w.json"));
    EXPECT_EQ(j["sky"]["type"], "perez");
    EXPECT_NEAR(j["sky"]["sun_altitude_deg"].get<double>(), 68.4, 0.3);
    EXPECT_NEAR(j["sky"]["horizontal_illuminance_lux"].get<double>(), j["sky"]["diffuse_horizontal_lux"].get<double>(),
                1e-6 * j["sky"]["diffuse_horizontal_lux"].get<double>());
    EXPECT_EQ(j["sky"]["illuminance_from"], "irradiance x Perez 1990 efficacy");
    EXPECT_GT(j["mean_luminance_cd_m2"].get<double>(), 0.0);
    const std::string out = " --out " + dir + "/x.exr --paths 1000 --no-progress";
    expectError(run("render " + scene + out + " --weather " + epw), 1, "--weather needs --weather-hour");
    expectError(run("render " + scene + out + " --weather-hour 06-21:13"), 1, "--weather-hour needs --weather");
    expectError(run("render " + scene + out + " --weather " + epw + " --weather-hour 6/21"), 1, "--weather-hour '6/21'");
    expectError(run("render " + scene + out + " --weather " + epw + " --weather-hour 06-21:13 --sky cie:12"), 1,
                "--sky cannot be given with it");
    expectError(run("render " + scene + out + " --weather " + epw + " --weather-hour 01-01:02"), 1,
                "tmy_45.000_8.000_2005_2016.epw:10 (1-1 hour 2): the sun is");
    expectError(run("render " + scene + out + " --weather " + dir + "/none.epw --weather-hour 06-21:13"), 1,
                "none.epw: cannot open the weather file");
    expectError(run("render " + scene + out + " --weather " + epw + " --weather-hour 06-21:13 --daylight-factor "
                    "--work-plane floor"), 1, "--daylight-factor is defined under the CIE overcast sky with no sun; leave out --weather");
}

// An annual study of the shipped room over the shipped year (DESIGN.md §8): its files, its JSON and
// its one-line errors.
TEST(CliAnnual, AYearOfTheShippedWeatherOnTheRoom)
{
    const std::string epw = std::string(FEN_SCENES_DIR) + "/weather/tmy_45.000_8.000_2005_2016.epw";
    const std::string scene = std::string(FEN_SCENES_DIR) + "/room.gltf";
    const std::string dir = test::tempDir("cli-annual");
    const CliRun r = run("render " + scene + " --out " + dir + "/a --annual " + epw +
                         " --work-plane floor --sensor-spacing 0.5 --paths 2000000 --no-progress");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("annual: "), std::string::npos) << r.out;
    const auto j = nlohmann::json::parse(slurp(dir + "/a.json"));
    const auto& a = j["annual"];
    ASSERT_TRUE(a.is_object()) << j.dump();
    EXPECT_EQ(a["occupied_hours"], 3650);
    EXPECT_EQ(a["sky_patches"], 146);
    EXPECT_EQ(a["missing_hours"], 0);
    EXPECT_EQ(a["learning"], "year");
    EXPECT_EQ(a["occupied_hours"].get<int>(), a["daylit_hours"].get<int>() + a["dark_hours"].get<int>());
    for (const char* k : {"sda_pct", "ase_pct", "mean_da_pct", "mean_udi_useful_pct"}) {
        EXPECT_GE(a[k].get<double>(), 0.0) << k;
        EXPECT_LE(a[k].get<double>(), 100.0) << k;
    }
    EXPECT_GT(a["mean_lux"].get<double>(), 0.0);
    EXPECT_EQ(j["sky"]["type"], "uniform");
    EXPECT_NEAR(j["sky"]["ground_luminance_cd_m2"].get<double>(), 1.0, 1e-12);
    EXPECT_TRUE(j["sun"].is_null());
    // One CSV row per cell, the matrices in Radiance's format.
    const std::string csv = slurp(dir + "/a.annual.csv");
    const std::size_t cells = j["sensors"]["workplane"]["cells"].get<std::size_t>();
    EXPECT_EQ(static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')), cells + 1);
    EXPECT_EQ(csv.rfind("sensor,cell,x_m,y_m,z_m,nx,ny,nz,area_m2,mean_lux,mean_std_err_lux,da_pct,", 0), 0u);
    for (const char* m : {"/a.dc.mtx", "/a.dc-direct.mtx"}) {
        const std::string mtx = slurp(dir + m);
        EXPECT_EQ(mtx.rfind("#?RADIANCE\n", 0), 0u) << m;
        EXPECT_NE(mtx.find("NROWS=" + std::to_string(cells) + "\nNCOLS=146\nNCOMP=3\nFORMAT=ascii\n\n"), std::string::npos) << m;
    }
    EXPECT_FALSE(slurp(dir + "/a.annual.png").empty());
    // The sun apart from the sky by default (five-phase); in its patch (two-phase) on request: the
    // same render, so the same coefficients, and the year's metrics from the other sun.
    EXPECT_EQ(a["sun"], "exact");
    EXPECT_EQ(a["sun_points"], 4);
    // 4 x 4 a cell for every daylit hour with direct sun (most of them)
    const auto samples = a["direct_sun_samples"].get<std::uint64_t>();
    EXPECT_EQ(samples % (16 * cells), 0u);
    EXPECT_GT(samples, 16 * cells * a["daylit_hours"].get<std::uint64_t>() / 2);
    EXPECT_LE(samples, 16 * cells * a["daylit_hours"].get<std::uint64_t>());
    EXPECT_NE(csv.find(",ase_hours,sun_mean_lux\n"), std::string::npos);
    EXPECT_GT(j["kernels"]["direct_sun"]["launches"].get<int>(), 0) << j["kernels"].dump();
    const CliRun p = run("render " + scene + " --out " + dir + "/p --annual " + epw +
                         " --work-plane floor --sensor-spacing 0.5 --paths 2000000 --no-progress --annual-sun patch");
    ASSERT_EQ(p.status, 0) << p.err;
    const auto pa = nlohmann::json::parse(slurp(dir + "/p.json"))["annual"];
    EXPECT_EQ(pa["sun"], "patch");
    EXPECT_TRUE(pa["sun_points"].is_null());
    EXPECT_EQ(pa["direct_sun_samples"], 0);
    for (const char* m : {".dc.mtx", ".dc-direct.mtx"})
        EXPECT_EQ(slurp(dir + "/p" + m), slurp(dir + "/a" + m)) << m;
    EXPECT_NEAR(pa["mean_lux"].get<double>(), a["mean_lux"].get<double>(), 0.05 * a["mean_lux"].get<double>());
    const std::string out = " --out " + dir + "/x --paths 1000 --no-progress";
    const std::string ann = " --annual " + epw + " --work-plane floor";
    expectError(run("render " + scene + out + " --sky-patches 2"), 1, "need --annual FILE.epw");
    expectError(run("render " + scene + out + ann + " --sky-patches 0"), 1, "--sky-patches 0: must be 1..16");
    expectError(run("render " + scene + out + ann + " --occupied 18-8"), 1, "--occupied '18-8': expected FROM-TO");
    expectError(run("render " + scene + out + ann + " --udi 2000,100"), 1, "--udi '2000,100': expected LOW,HIGH");
    expectError(run("render " + scene + out + ann + " --da-lux -3"), 1, "--da-lux -3: must be an illuminance");
    expectError(run("render " + scene + out + ann + " --annual-learning some"), 1, "--annual-learning 'some': expected year or unit");
    expectError(run("render " + scene + out + ann + " --adaptive-openings-share 0.5"), 1,
                "--adaptive-openings-share: does not apply to an --annual study (the light a walk brings in has no sky "
                "patch of its own)");
    expectError(run("render " + scene + out + ann + " --annual-sun fixed"), 1, "--annual-sun 'fixed': expected exact or patch");
    expectError(run("render " + scene + out + ann + " --annual-sun patch --annual-sun-points 4"), 1,
                "--annual-sun-points: only with --annual-sun exact");
    expectError(run("render " + scene + out + ann + " --annual-sun-points 0"), 1, "--annual-sun-points 0: must be 1..16");
    expectError(run("render " + scene + out + ann + " --sky cie:12"), 1, "--annual takes its skies from the weather file");
    expectError(run("render " + scene + out + ann + " --daylight-factor"), 1, "--annual and --daylight-factor");
    expectError(run("render " + scene + out + " --annual " + dir + "/none.epw --work-plane floor"), 1,
                "none.epw: cannot open the weather file");
    expectError(run("render " + scene + out + " --annual " + epw), 1, "--no-image renders sensors alone");
    // 200,000 cells x 36,866 patches: 236 GB of sums, refused before anything is computed
    expectError(run("render " + scene + out + ann + " --sensor-spacing 0.01 --sky-patches 16"), 1,
                "--annual: the daylight coefficients of 200000 cells x 36866 sky patches need");
}

TEST(CliAnnual, AStoppedStudyResumesToTheSameCoefficients)
{
    // SIGTERM stops an annual study partway; --resume finishes it, and the coefficient matrices
    // and the year's metrics are the bytes of the study never stopped. The stop comes 40 % into the
    // uninterrupted study's render time, after its set-up (both from its JSON) less its kernel
    // build: that run compiled the kernels, the stopped one finds them in the cache (a cold build
    // of several seconds had put the stop after the end).
    const std::string epw = std::string(FEN_SCENES_DIR) + "/weather/tmy_45.000_8.000_2005_2016.epw";
    const std::string scene = std::string(FEN_SCENES_DIR) + "/room.gltf";
    const std::string dir = test::tempDir("cli-annual-resume");
    const std::string args = " --annual " + epw + " --work-plane floor --sensor-spacing 1 --paths 16777216 "
                             "--batches 64 --seed 4 --no-progress";
    const CliRun whole = run("render " + scene + " --out " + dir + "/whole" + args);
    ASSERT_EQ(whole.status, 0) << whole.err;
    const auto wj = nlohmann::json::parse(slurp(dir + "/whole.json"));
    const double setup = wj["seconds"]["total"].get<double>() - wj["seconds"]["render"].get<double>() -
                         wj["seconds"]["kernel_build"].get<double>();
    const double stopAt = setup + 0.4 * wj["seconds"]["render"].get<double>();
    char sleep[32];
    std::snprintf(sleep, sizeof sleep, "%.2f", stopAt);
    const std::string cmd = std::string(FENESTRA_BIN) + " render " + scene + " --out " + dir + "/r" + args +
                            " --checkpoint " + dir + "/c.ckpt >/dev/null 2>" + dir + "/err & pid=$!; sleep " + sleep +
                            "; kill -TERM $pid; wait $pid; echo $? >" + dir + "/status";
    ASSERT_EQ(std::system(("bash -c '" + cmd + "'").c_str()), 0);
    ASSERT_EQ(std::stoi(slurp(dir + "/status")), 130) << slurp(dir + "/err");
    const CliRun r = run("render " + scene + " --out " + dir + "/r" + args + " --resume " + dir + "/c.ckpt");
    ASSERT_EQ(r.status, 0) << r.err;
    for (const char* file : {".dc.mtx", ".dc-direct.mtx", ".annual.csv", ".sensors.csv"})
        EXPECT_EQ(slurp(dir + "/r" + file), slurp(dir + "/whole" + file)) << file;
    const auto j = nlohmann::json::parse(slurp(dir + "/r.json"));
    EXPECT_GT(j["checkpoint"]["resumed_batches"].get<int>(), 0);
    EXPECT_LT(j["checkpoint"]["resumed_batches"].get<int>(), 64);
    // a checkpoint of another year's weighting is refused, naming it
    expectError(run("render " + scene + " --out " + dir + "/x" + args + " --annual-learning unit --resume " + dir +
                    "/c.ckpt"),
                1, "sky_patch_weights");
}

// Textures a scene cannot have: a missing file, bytes that are no image, an image too large.
TEST(CliBlender, BadTexturesAreOneLineErrorsNamingTheImage)
{
    const std::string dir = test::tempDir("cli-bad-texture");
    std::filesystem::create_directories(dir + "/textures");
    std::string twin = slurp(std::string(FEN_SCENES_DIR) + "/blender_room_twin.gltf");
    const auto variant = [&](const std::string& uri, const std::string& file) {
        std::string g = twin;
        const std::string from = "\"uri\": \"textures/floor_planks.png\"";
        const std::size_t at = g.find(from);
        EXPECT_NE(at, std::string::npos);
        g.replace(at, from.size(), "\"uri\": \"" + uri + "\"");
        std::ofstream(dir + "/" + file) << g;
        return dir + "/" + file;
    };
    const std::string args = " --out " + dir + "/o.exr --paths 1000 --sky cie:12 --sky-lux 1000 --no-progress";
    expectError(run("render " + variant("textures/missing.png", "a.gltf") + args), 1, "images[0] 'textures/missing.png'");
    std::ofstream(dir + "/textures/text.png") << "this is not a picture";
    expectError(run("render " + variant("textures/text.png", "b.gltf") + args), 1, "images[0] 'textures/text.png': not a PNG or JPEG");
    // A PNG header claiming 20000 x 20000 texels: refused by its size before anything is decoded.
    std::string png = slurp(std::string(FEN_SCENES_DIR) + "/textures/floor_planks.png");
    const unsigned char big[8] = {0, 0, 0x4e, 0x20, 0, 0, 0x4e, 0x20};
    png.replace(16, 8, reinterpret_cast<const char*>(big), 8);
    std::ofstream(dir + "/textures/big.png", std::ios::binary) << png;
    expectError(run("render " + variant("textures/big.png", "c.gltf") + args), 1, "20000 x 20000 texels");
    std::string trunc = slurp(std::string(FEN_SCENES_DIR) + "/textures/floor_planks.png").substr(0, 60);
    std::ofstream(dir + "/textures/trunc.png", std::ios::binary) << trunc;
    expectError(run("render " + variant("textures/trunc.png", "d.gltf") + args), 1, "images[0] 'textures/trunc.png': unreadable PNG");
}


// Outputs are created with the user's umask, as any new file is (they were always 0644).
TEST(CliRender, OutputsFollowTheUmask)
{
    const std::string dir = test::tempDir("cli-umask");
    for (const auto& [mask, mode] : {std::pair<const char*, unsigned>{"077", 0600u}, {"022", 0644u}, {"002", 0664u}}) {
        const std::string out = dir + "/u" + mask + ".exr";
        const CliRun r = run("render " + std::string(FEN_SCENES_DIR) + "/room.gltf --out " + out +
                                 " --paths 20000 --width 16 --no-progress",
                             std::string("umask ") + mask + ";");
        ASSERT_EQ(r.status, 0) << r.err;
        for (const std::string& f : {out, dir + "/u" + mask + ".json", dir + "/u" + mask + ".png"}) {
            const auto p = std::filesystem::status(f).permissions();
            EXPECT_EQ(static_cast<unsigned>(p) & 0777u, mode) << f << " under umask " << mask;
        }
    }
}


// The outputs are one set: a render killed between the renames of its files leaves a journal, and
// the next render into that --out finishes them before anything else (here a render that then
// fails on an unknown camera), so the set is wholly the killed render's, bit for bit, with no
// temporary left. A second render into the same --out while one runs is refused at once.
TEST(CliRender, OutputsAreCommittedAsASetAndLocked)
{
    const std::string dir = test::tempDir("cli-set");
    const std::string scene = std::string(FEN_SCENES_DIR) + "/room.gltf";
    const std::string args = " --paths 40000 --width 32 --no-progress";
    ASSERT_EQ(run("render " + scene + " --out " + dir + "/old/r.exr --seed 3" + args).status, 0);
    ASSERT_EQ(run("render " + scene + " --out " + dir + "/want/r.exr --seed 7" + args).status, 0);
    // The old set, then seed 7 killed after two of its four renames: a mixed set, and a journal.
    std::filesystem::copy(dir + "/old", dir + "/out");
    const CliRun k = run("render " + scene + " --out " + dir + "/out/r.exr --seed 7" + args, "FEN_KILL_AFTER_RENAMES=2");
    EXPECT_EQ(k.status, 128 + 9) << k.err;
    EXPECT_TRUE(std::filesystem::exists(dir + "/out/.r.exr.commit"));
    EXPECT_NE(slurp(dir + "/out/r.json"), slurp(dir + "/want/r.json"));  // not yet renamed
    // Any render into that --out first finishes the set (this one then stops at its unknown camera).
    const CliRun f = run("render " + scene + " --out " + dir + "/out/r.exr --camera nobody" + args);
    EXPECT_EQ(f.status, 1) << f.err;
    EXPECT_NE(f.err.find("finished writing the 2 outputs of a render killed"), std::string::npos) << f.err;
    for (const char* name : {"r.exr", "r.noise.exr", "r.png"})
        EXPECT_TRUE(slurp(dir + "/out/" + name) == slurp(dir + "/want/" + name)) << name << " differs";
    const auto jo = nlohmann::json::parse(slurp(dir + "/out/r.json")), jw = nlohmann::json::parse(slurp(dir + "/want/r.json"));
    for (const char* key : {"seed", "paths", "mean_luminance_cd_m2", "noise_std_err_cd_m2"})
        EXPECT_EQ(jo[key], jw[key]) << key;
    EXPECT_EQ(jo["emission"]["checksum"], jw["emission"]["checksum"]);
    for (const auto& e : std::filesystem::directory_iterator(dir + "/out"))
        EXPECT_TRUE(e.path().filename().string()[0] != '.') << "left behind: " << e.path();
    // An orphan temporary from a render killed while writing is removed too.
    std::ofstream(dir + "/out/.r.png.Ab12Cd") << "half a PNG";
    ASSERT_EQ(run("render " + scene + " --out " + dir + "/out/r.exr" + args).status, 0);
    EXPECT_FALSE(std::filesystem::exists(dir + "/out/.r.png.Ab12Cd"));

    // The lock: a long render holds it, a second one into the same --out is refused at once.
    const std::string bg = dir + "/bg.pid";
    std::system((std::string("sh -c '") + FENESTRA_BIN + " render " + scene + " --out " + dir +
                 "/out/r.exr --time 30 --width 32 --no-progress >/dev/null 2>&1 & echo $! > " + bg + "'").c_str());
    for (int i = 0; i < 100 && !std::filesystem::exists(dir + "/out/.r.exr.lock"); ++i)
        ::usleep(50000);
    const CliRun second = run("render " + scene + " --out " + dir + "/out/r.exr" + args);
    expectError(second, 1, "another render is writing these outputs now");
    std::system(("kill -9 $(cat " + bg + ")").c_str());
}


// Values that used to stand for "not given" fell back to the default without a word; each is now
// an error naming the option, the value and the range, before anything is loaded.
TEST(CliRender, OutOfRangeOptionsAreErrorsNotDefaults)
{
    const std::string dir = test::tempDir("cli-ranges");
    const std::string good = plateScene().write(dir + "/good.gltf");
    const std::string out = " --out " + dir + "/o.exr --no-progress";
    const std::pair<const char*, const char*> cases[] = {
        {" --paths 1000 --width 0", "--width 0: must be in 1..16384"},
        {" --paths 1000 --width 0 --height 0", "--width 0"},
        {" --paths 1000 --height -3", "--height -3"},
        {" --time 0 --paths 1000", "give either --paths or --time, not both"},
        {" --time 0", "--time 0: must be a positive, finite number"},
        {" --time nan", "--time nan"},
        {" --paths 1000 --checkpoint ''", "--checkpoint '': give a file name"},
        {" --paths 1000 --split-weight nan", "--split-weight nan"},
        {" --paths 1000 --split-weight -1", "--split-weight -1"},
        {" --paths 1000 --max-bounces -1", "--max-bounces -1"},
        {" --paths 1000 --roulette-depth -1", "--roulette-depth -1"},
        {" --paths 1000 --seed -1", "--seed -1"},
        {" --paths 1000 --seed 4294967296", "--seed 4294967296"},
        {" --paths 1000 --batches 1", "--batches 1: must be in 2..65536"},
        {" --paths 1000 --camera-spp 0", "--camera-spp 0"},
        {" --paths 1000 --camera-pass adaptive", "--camera-pass 'adaptive'"},
        {" --paths 1000 --pool 0", "--pool 0"},
        {" --paths 1000 --exposure 0", "--exposure 0"},
        {" --paths 72057594037927937", "--paths 72057594037927937: must be a whole number from 1 to 2^56"},
        {" --paths 2.5", "--paths 2.5"},
        {" --paths -1", "--paths -1"},
        {" --paths many", "--paths many"},
        {" --paths 1000 --kernels fast", "--kernels 'fast'"},
        {" --paths 1000 --layout bvh3", "--layout 'bvh3'"},
        {" --paths 1000 --progress --no-progress", "not both"},
        {" --paths 1000 --method portal --portals plate --portal-complement -0.5", "--portal-complement"},
        {" --paths 1000 --adaptive-first-pass 0", "--adaptive-first-pass"},
        {" --paths 1000 --adaptive-max-cells 0", "--adaptive-max-cells"},
        {" --paths 1000 --adaptive-defensive nan", "--adaptive-defensive nan"},
        {" --paths 1000 --adaptive-max-depth -1", "--adaptive-max-depth -1"},
        {" --paths 1000 --adaptive-prior -3", "--adaptive-prior"},
    };
    for (const auto& [args, fragment] : cases)
        expectError(run("render " + good + out + args), 1, fragment);
    // Beyond 2^63 - 1: refused as typed (it used to be clamped to 2^63 - 1 and never end).
    expectError(run("render " + good + out + " --paths 18446744073709551615"), 1, "--paths 18446744073709551615:");
    // Grid depths whose first cells no machine holds: the cell limit's error at once, naming the
    // options (it used to allocate them all and fail after seconds with "out of host memory").
    const CliRun deep = run("render " + std::string(FEN_SCENES_DIR) + "/bay_window.gltf" + out +
                            " --paths 1000 --base portal --adaptive-initial-depth 6 --adaptive-max-depth 8"
                            " --adaptive-initial-sky-depth 5 --adaptive-max-sky-depth 6");
    expectError(deep, 1, "--adaptive-max-cells 32768 is below the");
    EXPECT_NE(deep.err.find("lower --adaptive-initial-depth"), std::string::npos) << deep.err;
    // Scientific notation is a count when it is a whole number.
    EXPECT_EQ(run("render " + good + out + " --paths 2e4 --width 8").status, 0);
}

// The ground's glow (DESIGN.md §1): its albedo from the file or --ground-albedo (which overrides
// it; 0 is off), reported with the luminance it glows at, L_g = albedo E_h / pi (E_h the sky's and
// the sun's horizontal illuminance); an albedo outside [0, 1] is a one-line error naming the key
// or the option.
TEST(CliRender, GroundGlowIsReportedAndItsAlbedoChecked)
{
    const std::string dir = test::tempDir("cli-ground");
    test::GltfWriter w = plateScene();
    w.doc()["scenes"][0]["extras"]["sky"]["ground_albedo"] = 0.25;
    const std::string scene = w.write(dir + "/ground.gltf");
    const std::string args = " --paths 20000 --width 16 --no-progress";
    const auto sky = [&](const std::string& scenePath, const std::string& name, const std::string& more) {
        const CliRun r = run("render " + scenePath + " --out " + dir + "/" + name + ".exr" + args + more);
        EXPECT_EQ(r.status, 0) << r.err;
        return nlohmann::json::parse(slurp(dir + "/" + name + ".json"));
    };
    nlohmann::json j = sky(scene, "file", "");
    const double E = j["sky"]["horizontal_illuminance_lux"].get<double>();  // no sun: the sky's alone
    EXPECT_NEAR(E, M_PI * 1000.0, 1e-6 * E);
    EXPECT_EQ(j["sky"]["ground_albedo"].get<double>(), 0.25);
    EXPECT_NEAR(j["sky"]["ground_luminance_cd_m2"].get<double>(), 0.25 * E / M_PI, 1e-9 * E);
    j = sky(scene, "off", " --ground-albedo 0");
    EXPECT_EQ(j["sky"]["ground_albedo"].get<double>(), 0.0);
    EXPECT_EQ(j["sky"]["ground_luminance_cd_m2"].get<double>(), 0.0);
    j = sky(scene, "half", " --ground-albedo 0.5");
    EXPECT_NEAR(j["sky"]["ground_luminance_cd_m2"].get<double>(), 0.5 * E / M_PI, 1e-9 * E);
    // The sun adds E_sun sin(altitude): the room's 75,000 lux sun, its CIE clear sky.
    j = sky(std::string(FEN_SCENES_DIR) + "/room.gltf", "room", " --ground-albedo 0.2");
    const double Eh = j["sky"]["horizontal_illuminance_lux"].get<double>() +
                      75000.0 * std::sin(j["sun"]["altitude_deg"].get<double>() * M_PI / 180.0);
    EXPECT_NEAR(j["sky"]["ground_luminance_cd_m2"].get<double>(), 0.2 * Eh / M_PI, 1e-6 * Eh);
    EXPECT_EQ(sky(std::string(FEN_SCENES_DIR) + "/room.gltf", "room0", "")["sky"]["ground_luminance_cd_m2"], 0.0);
    expectError(run("render " + scene + " --out " + dir + "/x.exr" + args + " --ground-albedo 1.5"), 1,
                "--ground-albedo 1.5: must be in 0..1");
    expectError(run("render " + scene + " --out " + dir + "/x.exr" + args + " --ground-albedo -0.1"), 1,
                "--ground-albedo -0.1");
    expectError(run("render " + scene + " --out " + dir + "/x.exr" + args + " --sky none --ground-albedo 0.3"), 1,
                "--ground-albedo: the scene has no sky");
    w.doc()["scenes"][0]["extras"]["sky"]["ground_albedo"] = 2;
    expectError(run("render " + w.write(dir + "/bad.gltf") + " --out " + dir + "/x.exr" + args), 1,
                "bad.gltf: scenes[0].extras.sky.ground_albedo: 2 is outside [0, 1]");
}

// Outputs never overwrite what the render reads, a checkpoint overwrites only a checkpoint, and a
// FIFO given as a checkpoint to resume is refused at once instead of blocking for ever.
TEST(CliRender, OutputsNeverOverwriteInputs)
{
    const std::string dir = test::tempDir("cli-overwrite");
    const std::string scene = plateScene().write(dir + "/scene.gltf");
    const std::string sceneBytes = slurp(scene);
    const std::string args = " --paths 20000 --width 16 --no-progress";
    ASSERT_EQ(run("render " + scene + " --out " + dir + "/ref.exr" + args).status, 0);
    const std::string refBytes = slurp(dir + "/ref.exr");
    expectError(run("render " + scene + " --out " + dir + "/o.exr --checkpoint " + scene + args), 1, "--checkpoint");
    EXPECT_EQ(slurp(scene), sceneBytes);
    expectError(run("render " + scene + " --out " + dir + "/o.exr --checkpoint " + dir + "/ref.exr --reference " + dir +
                    "/ref.exr" + args),
                1, "--checkpoint");
    expectError(run("render " + scene + " --out " + dir + "/ref.exr --reference " + dir + "/./ref.exr" + args), 1,
                "is the --reference image");
    std::filesystem::create_symlink(dir + "/ref.exr", dir + "/link.exr");
    expectError(run("render " + scene + " --out " + dir + "/link.exr --reference " + dir + "/ref.exr" + args), 1,
                "is the --reference image");
    EXPECT_EQ(slurp(dir + "/ref.exr"), refBytes);
    // A scene's buffer is an input too.
    const std::string ext = plateScene().writeExternal(dir + "/ext.gltf", "buffer.exr");
    const std::string buffer = slurp(dir + "/buffer.exr");
    expectError(run("render " + ext + " --out " + dir + "/buffer.exr" + args), 1, "is a file the scene reads");
    EXPECT_EQ(slurp(dir + "/buffer.exr"), buffer);
    ASSERT_EQ(::mkfifo((dir + "/pipe").c_str(), 0600), 0);
    expectError(run("render " + scene + " --out " + dir + "/o.exr --resume " + dir + "/pipe" + args, "timeout 20"), 1,
                "--resume must be a regular file, not a FIFO");
}

// Names are bytes: a Latin-1 name (a shared drive's) reaches the file system unchanged and the JSON
// as valid UTF-8, its stray bytes as \xNN; the render no longer fails at the end.
TEST(CliRender, NonUtf8NamesAreWrittenNotLost)
{
    const std::string dir = test::tempDir("cli-latin1");
    const std::string scene = plateScene().write(dir + "/sc\xE8ne.gltf");  // the scene's name too
    const std::string out = dir + "/caf\xE9.exr", ckpt = dir + "/r\xE9sum\xE9.ckpt";
    const CliRun r = run("render '" + scene + "' --out '" + out + "' --checkpoint '" + ckpt +
                         "' --checkpoint-every 4batches --region 's\xFC" "d=0,0,8,8' --paths 20000 --width 16 --no-progress");
    ASSERT_EQ(r.status, 0) << r.err;
    ASSERT_TRUE(std::filesystem::exists(out));
    ASSERT_TRUE(std::filesystem::exists(dir + "/caf\xE9.json"));
    const auto j = nlohmann::json::parse(slurp(dir + "/caf\xE9.json"));
    EXPECT_NE(j["outputs"]["exr"].get<std::string>().find("caf\\xE9.exr"), std::string::npos);
    EXPECT_TRUE(j["regions"].contains("s\\xFCd"));
    EXPECT_NE(j["scene"].get<std::string>().find("sc\\xE8ne.gltf"), std::string::npos);
    // The checkpoint written under that name resumes.
    ASSERT_TRUE(std::filesystem::exists(ckpt));
    const CliRun q = run("render '" + scene + "' --out '" + dir + "/again.exr' --resume '" + ckpt +
                         "' --region 's\xFC" "d=0,0,8,8' --paths 20000 --width 16 --no-progress");
    EXPECT_EQ(q.status, 0) << q.err;
    EXPECT_EQ(slurp(dir + "/again.exr"), slurp(out));
}


// A stop arrives within about a second whatever the batch size (it used to wait for the batch in
// flight: minutes at --paths 2e9): the paths in flight finish, none start, and the image is that of
// the paths traced. SIGINT, SIGTERM and SIGHUP (a closed terminal) alike.
TEST(CliRender, AStopEndsTheRenderWithinAboutASecond)
{
    const std::string dir = test::tempDir("cli-stop-fast");
    const std::string scene = plateScene().write(dir + "/plate.gltf");
    for (const char* sig : {"INT", "HUP", "TERM"}) {
        const std::string out = dir + "/" + sig;
        // Two batches of 2e9 paths each: one batch alone takes minutes on two cores.
        const std::string cmd = std::string(FENESTRA_BIN) + " render " + scene + " --out " + out +
                                ".exr --paths 4e9 --batches 2 --width 40 --no-progress 2>" + out +
                                ".err & pid=$!; sleep 3; s=$(date +%s%N); kill -" + sig +
                                " $pid; wait $pid; echo $? $(( ($(date +%s%N) - s) / 1000000 )) >" + out + ".status";
        ASSERT_EQ(std::system(("bash -c '" + cmd + "'").c_str()), 0);
        std::istringstream st(slurp(out + ".status"));
        int status = 0, ms = 0;
        st >> status >> ms;
        EXPECT_EQ(status, 130) << sig << ": " << slurp(out + ".err");
        EXPECT_LT(ms, 2500) << sig << ": took " << ms << " ms to stop";
        std::printf("[ stop ] SIG%s: exited %d, %d ms after the signal\n", sig, status, ms);
        const auto j = nlohmann::json::parse(slurp(out + ".json"));
        EXPECT_TRUE(j["interrupted"].get<bool>()) << sig;
        EXPECT_EQ(j["batches"], 1) << sig;  // the batch in flight, cut short: its paths are the image
        EXPECT_GT(j["paths"].get<std::uint64_t>(), 0u) << sig;
        EXPECT_LT(j["paths"].get<std::uint64_t>(), 2000000000u) << sig;
        EXPECT_GT(j["mean_luminance_cd_m2"].get<double>(), 0.0) << sig;
        EXPECT_EQ(j["counters"]["bad_contributions"], 0) << sig;
    }
}

// Stopped in the middle of a batch of a learning render, the checkpoint is the state after the
// batches done (the strategy's too, although it went on learning), and resuming it gives the
// image of the render never stopped, bit for bit.
TEST(CliRender, AStopMidBatchStillResumesBitIdentically)
{
    const std::string dir = test::tempDir("cli-stop-resume");
    const std::string scene = std::string(FEN_SCENES_DIR) + "/room.gltf";
    const std::string args = " --paths 24000000 --batches 4 --width 32 --seed 9 --no-progress";
    ASSERT_EQ(run("render " + scene + " --out " + dir + "/whole.exr" + args).status, 0);
    // Stop just after the first batch's checkpoint appears: inside the second batch (a quarter of
    // the render, over a second on two cores).
    const std::string cmd = std::string(FENESTRA_BIN) + " render " + scene + " --out " + dir + "/r.exr" + args +
                            " --checkpoint " + dir + "/c.ckpt --checkpoint-every 1batches 2>" + dir +
                            "/err & pid=$!; while [ ! -e " + dir + "/c.ckpt ]; do sleep 0.02; done; kill -INT $pid; "
                            "wait $pid; echo $? >" + dir + "/status";
    ASSERT_EQ(std::system(("bash -c '" + cmd + "'").c_str()), 0);
    const int status = std::stoi(slurp(dir + "/status"));
    if (status == 0)
        GTEST_SKIP() << "the render finished before the signal";
    ASSERT_EQ(status, 130) << slurp(dir + "/err");
    const auto j = nlohmann::json::parse(slurp(dir + "/r.json"));
    EXPECT_LT(j["batches"].get<int>(), 4);
    const CliRun r = run("render " + scene + " --out " + dir + "/r.exr" + args + " --resume " + dir + "/c.ckpt");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(slurp(dir + "/r.exr") == slurp(dir + "/whole.exr")) << "resumed image differs";
}

// A checkpoint that cannot be written (a full disk) ends the render after the image of the batches
// done is written, with a one-line error; it used to end it with nothing written.
TEST(CliRender, AFailedCheckpointStillWritesTheImage)
{
    const std::string dir = test::tempDir("cli-ckpt-fail");
    const std::string scene = plateScene().write(dir + "/plate.gltf");
    const CliRun r = run("render " + scene + " --out " + dir + "/r.exr --paths 400000 --batches 8 --width 16 "
                         "--checkpoint " + dir + "/c.ckpt --checkpoint-every 2batches --no-progress",
                         "FEN_FAIL_WRITE=c.ckpt");
    expectError(r, 1, "c.ckpt: cannot write");
    EXPECT_NE(r.err.find("outputs hold the 2 batches finished"), std::string::npos) << r.err;
    const auto j = nlohmann::json::parse(slurp(dir + "/r.json"));
    EXPECT_EQ(j["batches"], 2);
    EXPECT_GT(j["mean_luminance_cd_m2"].get<double>(), 0.0);
}


// A checkpoint whose checksum was recomputed after an edit passes the checksum, not the meaning:
// a per-batch count that would hang the render, a NaN or negative film sum are refused in one line.
TEST(CliRender, AnEditedCheckpointIsRefusedByWhatItSays)
{
    const std::string dir = test::tempDir("cli-ckpt-edit");
    const std::string scene = plateScene().write(dir + "/plate.gltf");
    const std::string args = " --paths 80000 --batches 8 --width 16 --no-progress";
    ASSERT_EQ(run("render " + scene + " --out " + dir + "/r.exr" + args + " --checkpoint " + dir +
                  "/c.ckpt --checkpoint-every 2batches").status, 0);
    const std::string good = slurp(dir + "/c.ckpt");
    // The value after `key` (its length, its bytes, then for an array its count) becomes `bits`,
    // and the checksum (FNV-1a 64 over everything before it) is made right again.
    const auto edited = [&](const std::string& key, bool array, std::uint64_t bits, const std::string& name) {
        std::string b = good;
        std::string tag(8, '\0');
        for (int i = 0; i < 8; ++i)
            tag[i] = static_cast<char>((key.size() >> (8 * i)) & 0xff);
        const std::size_t at = b.find(tag + key);
        EXPECT_NE(at, std::string::npos) << key;
        const std::size_t value = at + 8 + key.size() + (array ? 8 : 0);
        for (int i = 0; i < 8; ++i)
            b[value + i] = static_cast<char>((bits >> (8 * i)) & 0xff);
        std::uint64_t h = 1469598103934665603ull;
        for (std::size_t i = 0; i + 8 < b.size(); ++i)
            h = (h ^ static_cast<unsigned char>(b[i])) * 1099511628211ull;
        for (int i = 0; i < 8; ++i)
            b[b.size() - 8 + i] = static_cast<char>((h >> (8 * i)) & 0xff);
        std::ofstream(dir + "/" + name, std::ios::binary) << b;
        return dir + "/" + name;
    };
    const auto bitsOf = [](double d) {
        std::uint64_t u;
        std::memcpy(&u, &d, 8);
        return u;
    };
    const std::string resume = "render " + scene + " --out " + dir + "/x.exr" + args + " --resume ";
    expectError(run(resume + edited("loop.per_batch", false, std::uint64_t{1} << 60, "huge.ckpt")), 1, "loop.per_batch");
    expectError(run(resume + edited("film.sum", true, bitsOf(std::nan("")), "nan.ckpt")), 1, "film.sum");
    expectError(run(resume + edited("film.sum", true, bitsOf(-5.0), "negative.ckpt")), 1, "light is never negative");
    EXPECT_EQ(run(resume + edited("loop.per_batch", false, 10000, "same.ckpt")).status, 0);  // the edit machinery works
}

}  // namespace
}  // namespace fen

namespace fen {
namespace {

// The plate scene with a sensor node: a 1 x 1 m square 0.5 m above the plate, cells of 0.5 m.
test::GltfWriter plateWithSensorNode()
{
    test::GltfWriter w = plateScene();
    const int n = w.addMeshNode("desk", {{{-0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, -0.5f}},
                                         {{-0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, -0.5f}, {-0.5f, 0.5f, -0.5f}}});
    w.node(n)["extras"] = {{"sensor", {{"cell_m", 0.5}}}};
    return w;
}

TEST(CliSensors, NodesWorkPlanesAndPointsWriteCsvAndJson)
{
    // A daylight-factor study with no image: the scene's sensor node, a work plane over the plate
    // and a points file; every sensor unobstructed, so DF = 100 % within its noise (4 sigma).
    const std::string dir = test::tempDir("cli-sensors");
    const std::string scene = plateWithSensorNode().write(dir + "/plate.gltf");
    {
        std::ofstream pts(dir + "/grid.pts");
        pts << "# two points facing up, one facing south\n0.25 1 0.25 0 1 0\n-0.25 1 0.25 0 2 0\n\n0 1 0 0 0 1\n";
    }
    const CliRun r = run("render " + scene + " --out " + dir + "/df --no-image --daylight-factor --work-plane plate "
                         "--sensor-spacing 0.5 --sensor-points " + dir + "/grid.pts --sensor-size 0.5 --paths 2000000 "
                         "--no-progress");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(slurp(dir + "/df.exr").empty()) << "--no-image writes no image";
    EXPECT_TRUE(slurp(dir + "/df.png").empty());
    const std::string csv = slurp(dir + "/df.sensors.csv");
    EXPECT_EQ(csv.substr(0, csv.find('\n')),
              "sensor,cell,x_m,y_m,z_m,nx,ny,nz,area_m2,illuminance_lux,std_err_lux,daylight_factor_pct,"
              "daylight_factor_std_err_pct");
    // 4 cells on the desk, 16 on the work plane (2 x 2 m at 0.5 m), 3 points: in that order
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 4 + 16 + 3);
    EXPECT_NE(csv.find("\ngrid,0,0.25,1,0.25,0,1,0,0.25,"), std::string::npos) << csv;
    EXPECT_NE(csv.find("\ngrid,2,0,1,0,0,0,1,0.25,"), std::string::npos) << csv;
    const auto j = nlohmann::json::parse(slurp(dir + "/df.json"));
    EXPECT_EQ(j["image"], false);
    EXPECT_EQ(j["sky"]["cie_type"], 1);
    EXPECT_TRUE(j["sun"].is_null());
    for (const char* name : {"desk", "workplane"}) {
        const auto& d = j["sensors"][name]["daylight_factor"];
        const double df = d["mean_pct"], se = d["mean_pct_std_err"];
        std::printf("[ sensors  ] %s: DF %.3f %% +- %.3f\n", name, df, se);
        EXPECT_NEAR(df, 100.0, 4.0 * se) << name;
        EXPECT_LT(se, 1.0) << name;
        EXPECT_EQ(d["area_share_above"], 1.0) << name;
    }
    EXPECT_EQ(j["sensors"]["workplane"]["cells"], 16);
    EXPECT_EQ(j["sensors"]["workplane"]["kind"], "work plane");
    EXPECT_EQ(j["sensors"]["grid"]["cells"], 3);
    EXPECT_EQ(j["outputs"]["sensors_csv"], dir + "/df.sensors.csv");
    EXPECT_NE(r.out.find("sensor workplane: 16 cells"), std::string::npos) << r.out;
}

TEST(CliSensors, BadSensorsAreOneLineErrors)
{
    const std::string dir = test::tempDir("cli-sensors-bad");
    const std::string scene = plateScene().write(dir + "/plate.gltf");
    const std::string out = " --out " + dir + "/o.exr --paths 1000 --no-progress";
    const auto withPoints = [&](const std::string& name, const std::string& text) {
        std::ofstream(dir + "/" + name) << text;
        return run("render " + scene + out + " --sensor-points " + dir + "/" + name);
    };
    expectError(withPoints("a.pts", "0 1 0 0 1 0\n0 1 x 0 1 0\n"), 1, "a.pts:2: 'x' is not a finite number");
    expectError(withPoints("b.pts", "# ok\n\n0 1 0 0 1 0\n0 1 0 0 1\n"), 1, "b.pts:4: 5 numbers; expected six");
    expectError(withPoints("c.pts", "0 1 0 0 0 0\n"), 1, "c.pts:1: the direction (dx dy dz) is zero");
    expectError(withPoints("d.pts", "# nothing\n"), 1, "d.pts: --sensor-points: no points");
    expectError(withPoints("e.pts", "0 1 0 0 1 0\n"), 1, "one point, or all at one place: give its cell's side");
    expectError(run("render " + scene + out + " --sensor-points " + dir + "/none.pts"), 1, "none.pts");
    expectError(run("render " + scene + out + " --work-plane floor"), 1,
                "--work-plane floor: no node of that name in");
    expectError(run("render " + scene + out + " --sensor-spacing 0.1"), 1, "--sensor-spacing needs --work-plane");
    expectError(run("render " + scene + out + " --work-plane plate --sensor-spacing 0"), 1, "--sensor-spacing 0");
    expectError(run("render " + scene + out + " --no-image"), 1, "--no-image renders sensors alone");
    expectError(run("render " + scene + out + " --no-image --work-plane plate --width 40"), 1,
                "--width is about the image");
    expectError(run("render " + scene + out + " --no-image --work-plane plate --camera-pass fixed"), 1,
                "--camera-pass is about the image");
    expectError(run("render " + scene + out + " --daylight-factor --work-plane plate --sky uniform"), 1,
                "--daylight-factor is defined under the CIE overcast sky");
    expectError(run("render " + scene + out + " --daylight-factor --work-plane plate --sun 30,180"), 1,
                "--daylight-factor is defined with no sun");
    expectError(run("render " + scene + out + " --df-threshold 2 --work-plane plate"), 1,
                "--df-threshold needs --daylight-factor");
    // a work plane over a node with no floor: a vertical wall
    {
        test::GltfWriter w = plateScene();
        w.addMeshNode("wall", {{{-1, 0, -1}, {1, 0, -1}, {1, 2, -1}}});
        const std::string s2 = w.write(dir + "/wall.gltf");
        expectError(run("render " + s2 + out + " --work-plane wall"), 1, "the work plane meets no floor");
    }
    // sensor nodes: no area, a bad value, a portal that is a sensor, cells larger than the node
    {
        test::GltfWriter w = plateScene();
        const int n = w.addMeshNode("flat", {{{0, 1, 0}, {1, 1, 0}, {2, 1, 0}}});
        w.node(n)["extras"] = {{"sensor", true}};
        expectError(run("render " + w.write(dir + "/flat.gltf") + out), 1, "the sensor has no area");
    }
    {
        test::GltfWriter w = plateWithSensorNode();
        w.node(2)["extras"] = {{"sensor", {{"cell_m", -1}}}};
        expectError(run("render " + w.write(dir + "/neg.gltf") + out), 1, "extras.sensor.cell_m: -1");
        w.node(2)["extras"] = {{"sensor", "yes"}};
        expectError(run("render " + w.write(dir + "/str.gltf") + out), 1, "extras.sensor: must be true, false or");
        w.node(2)["extras"] = {{"sensor", true}, {"portal", true}};
        expectError(run("render " + w.write(dir + "/portal.gltf") + out), 1, "the node is also a portal");
        w.node(2)["extras"] = {{"sensor", {{"cell_m", 5}}}};
        expectError(run("render " + w.write(dir + "/big.gltf") + out), 1, "no cell of 5 m has its centre");
    }
}

}  // namespace
}  // namespace fen
