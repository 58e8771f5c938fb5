// batch_test.cpp — `fenestra batch` as a user runs it (host/batch/batch_cmd.h): a batch of mixed
// jobs writes the same image bytes as the same jobs run one by one with `fenestra render` (a job
// of the same geometry as the one before reusing its BVH); a job
// that fails is reported and the others go on; a rerun skips the jobs finished and unchanged, and
// runs one again when a file it read changes; a broken jobs file is one line naming the key.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "e2e/cli_run.h"
#include "support/gltf_writer.h"

namespace fen {
namespace {

using test::CliRun;
using test::expectError;
using test::run;
using test::slurp;

std::string quoted(const std::vector<std::string>& args)
{
    nlohmann::json j = args;
    return j.dump();
}

TEST(CliBatch, JobsWriteTheirRendersBytesAndAFailureDoesNotStopTheRest)
{
    const std::string dir = test::tempDir("cli-batch");
    const std::string scenes = std::string(FEN_SCENES_DIR);
    const std::string epw = scenes + "/weather/tmy_45.000_8.000_2005_2016.epw";
    // A copy of the room, so that the rerun below can change a file a job read.
    std::filesystem::copy_file(scenes + "/room.gltf", dir + "/room.gltf",
                               std::filesystem::copy_options::overwrite_existing);
    const std::vector<std::pair<std::string, std::vector<std::string>>> jobs = {
        {"adaptive", {dir + "/room.gltf", "--paths", "300000", "--width", "48", "--seed", "3", "--no-progress"}},
        {"weather", {scenes + "/room.gltf", "--weather", epw, "--weather-hour", "06-21:13", "--paths", "300000",
                     "--width", "48", "--no-progress"}},
        {"broken", {scenes + "/no_such_scene.gltf", "--paths", "1000", "--no-progress"}},
        {"uniform", {scenes + "/inner_room.gltf", "--method", "uniform", "--paths", "200000", "--width", "40",
                     "--no-progress"}},
        {"plane", {scenes + "/room.gltf", "--no-image", "--work-plane", "floor", "--paths", "200000", "--no-progress"}}};
    std::string text = "{\"jobs\": [";
    for (std::size_t i = 0; i < jobs.size(); ++i) {
        std::vector<std::string> args = jobs[i].second;
        args.push_back("--out");
        args.push_back(dir + "/batch_" + jobs[i].first + (jobs[i].first == "plane" ? "" : ".exr"));
        text += (i ? ", " : "") + std::string("{\"name\": \"") + jobs[i].first + "\", \"render\": " + quoted(args) + "}";
    }
    text += "]}";
    std::ofstream(dir + "/jobs.json") << text;

    const CliRun b = run("batch " + dir + "/jobs.json");
    EXPECT_EQ(b.status, 1) << b.err;  // one job failed, after all ran
    EXPECT_NE(b.err.find("broken: failed: "), std::string::npos) << b.err;
    EXPECT_NE(b.err.find("no_such_scene.gltf"), std::string::npos) << b.err;
    EXPECT_NE(b.err.find("fenestra: error: batch "), std::string::npos) << b.err;
    auto statuses = [&] {
        const auto s = nlohmann::json::parse(slurp(dir + "/jobs.summary.json"));
        std::vector<std::string> out;
        for (const auto& j : s["jobs"])
            out.push_back(j["status"]);
        return out;
    };
    EXPECT_EQ(statuses(), (std::vector<std::string>{"done", "done", "failed", "done", "done"}));
    const std::string csv = slurp(dir + "/jobs.summary.csv");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 6) << csv;
    // The summary carries each job's figures: an image's mean, a sensor's mean illuminance.
    const auto summary = nlohmann::json::parse(slurp(dir + "/jobs.summary.json"));
    EXPECT_GT(summary["jobs"][0]["mean_luminance_cd_m2"].get<double>(), 0.0);
    EXPECT_TRUE(summary["jobs"][4]["mean_luminance_cd_m2"].is_null());
    const double lux = summary["jobs"][4]["sensors"]["workplane"]["mean_lux"].get<double>();
    EXPECT_EQ(lux, nlohmann::json::parse(slurp(dir + "/batch_plane.json"))["sensors"]["workplane"]["mean_lux"].get<double>());
    EXPECT_NE(csv.find(",workplane="), std::string::npos) << csv;

    // The weather job renders the room the adaptive job did (another file, the same geometry): it
    // reuses that job's BVH and buffers, and its image is still the render's own (below).
    EXPECT_FALSE(nlohmann::json::parse(slurp(dir + "/batch_adaptive.json"))["bvh_reused"].get<bool>());
    EXPECT_TRUE(nlohmann::json::parse(slurp(dir + "/batch_weather.json"))["bvh_reused"].get<bool>());
    EXPECT_FALSE(nlohmann::json::parse(slurp(dir + "/batch_uniform.json"))["bvh_reused"].get<bool>());

    // The same jobs one by one: the same bytes.
    for (const auto& [name, args] : jobs) {
        if (name == "broken" || name == "plane")
            continue;
        std::string line = "render";
        for (const std::string& a : args)
            line += " '" + a + "'";
        const CliRun r = run(line + " --out " + dir + "/one_" + name + ".exr");
        ASSERT_EQ(r.status, 0) << r.err;
        const std::string one = slurp(dir + "/one_" + name + ".exr"), batch = slurp(dir + "/batch_" + name + ".exr");
        EXPECT_FALSE(one.empty());
        EXPECT_TRUE(one == batch) << name << ": the batch's image differs from the render's";
    }

    // A rerun skips what finished and is unchanged; a changed input runs its job again.
    const auto before = std::filesystem::last_write_time(dir + "/batch_uniform.exr");
    const CliRun again = run("batch " + dir + "/jobs.json");
    EXPECT_EQ(again.status, 1) << again.err;
    EXPECT_EQ(statuses(), (std::vector<std::string>{"skipped", "skipped", "failed", "skipped", "skipped"}));
    EXPECT_EQ(std::filesystem::last_write_time(dir + "/batch_uniform.exr"), before);
    std::ofstream(dir + "/room.gltf", std::ios::app) << "\n";  // the same scene, other bytes
    const CliRun changed = run("batch " + dir + "/jobs.json");
    EXPECT_EQ(statuses(), (std::vector<std::string>{"done", "skipped", "failed", "skipped", "skipped"})) << changed.err;
    const CliRun all = run("batch --rerun " + dir + "/jobs.json");
    EXPECT_EQ(statuses(), (std::vector<std::string>{"done", "done", "failed", "done", "done"})) << all.err;
}

TEST(CliBatch, AnAnnualJobWritesWhatItsRenderWrites)
{
    // An annual study in a batch: its coefficients and metrics are the render's, byte for byte, and
    // the summary carries its sDA and ASE.
    const std::string dir = test::tempDir("cli-batch-annual");
    const std::string scenes = std::string(FEN_SCENES_DIR);
    const std::vector<std::string> args = {scenes + "/room.gltf", "--annual", scenes + "/weather/tmy_45.000_8.000_2005_2016.epw",
                                           "--work-plane", "floor", "--sensor-spacing", "0.5", "--paths", "400000",
                                           "--no-progress"};
    std::vector<std::string> batchArgs = args;
    batchArgs.insert(batchArgs.end(), {"--out", dir + "/b"});
    std::ofstream(dir + "/jobs.json") << "{\"jobs\": [{\"name\": \"year\", \"render\": " + quoted(batchArgs) + "}]}";
    const CliRun b = run("batch " + dir + "/jobs.json");
    ASSERT_EQ(b.status, 0) << b.err;
    std::string line = "render";
    for (const std::string& a : args)
        line += " '" + a + "'";
    const CliRun r = run(line + " --out " + dir + "/one");
    ASSERT_EQ(r.status, 0) << r.err;
    for (const char* ext : {".dc.mtx", ".dc-direct.mtx", ".annual.csv"}) {
        const std::string one = slurp(dir + "/one" + ext), batch = slurp(dir + "/b" + ext);
        EXPECT_FALSE(one.empty()) << ext;
        EXPECT_TRUE(one == batch) << ext << ": the batch's differs from the render's";
    }
    const auto summary = nlohmann::json::parse(slurp(dir + "/jobs.summary.json"));
    const auto annual = nlohmann::json::parse(slurp(dir + "/one.json"))["annual"];
    EXPECT_EQ(summary["jobs"][0]["annual"]["sda_pct"], annual["sda_pct"]);
    EXPECT_EQ(summary["jobs"][0]["annual"]["ase_pct"], annual["ase_pct"]);
}

TEST(CliBatch, AStopEndsTheJobInFlightAndRunsNoMore)
{
    // Three long jobs; SIGINT after 3 s: the first stops as a render does (its outputs written,
    // exit 130), the others do not start, and the summary says so.
    const std::string dir = test::tempDir("cli-batch-stop");
    const std::string scene = std::string(FEN_SCENES_DIR) + "/room.gltf";
    std::string text = "{\"jobs\": [";
    for (int i = 0; i < 3; ++i)
        text += std::string(i ? ", " : "") + "{\"name\": \"j" + std::to_string(i) + "\", \"render\": [\"" + scene +
                "\", \"--time\", \"60\", \"--width\", \"32\", \"--no-progress\", \"--out\", \"" + dir + "/j" +
                std::to_string(i) + ".exr\"]}";
    std::ofstream(dir + "/jobs.json") << text << "]}";
    const std::string cmd = std::string(FENESTRA_BIN) + " batch " + dir + "/jobs.json 2>" + dir +
                            "/err & pid=$!; sleep 3; kill -INT $pid; wait $pid; echo $? >" + dir + "/status";
    ASSERT_EQ(std::system(("bash -c '" + cmd + "'").c_str()), 0);
    EXPECT_EQ(std::stoi(slurp(dir + "/status")), 130) << slurp(dir + "/err");
    const auto s = nlohmann::json::parse(slurp(dir + "/jobs.summary.json"));
    ASSERT_EQ(s["jobs"].size(), 3u);
    EXPECT_EQ(s["jobs"][0]["status"], "stopped");
    EXPECT_EQ(s["jobs"][1]["status"], "not run");
    EXPECT_EQ(s["jobs"][2]["status"], "not run");
    EXPECT_TRUE(nlohmann::json::parse(slurp(dir + "/j0.json"))["interrupted"].get<bool>());
    EXPECT_FALSE(std::filesystem::exists(dir + "/j1.json"));
}

TEST(CliBatch, AChangedWeatherFileRunsItsJobAgain)
{
    // The key covers every file a job read, not only its scene: the weather file here.
    const std::string dir = test::tempDir("cli-batch-weather");
    const std::string epw = dir + "/year.epw";
    std::filesystem::copy_file(std::string(FEN_SCENES_DIR) + "/weather/tmy_45.000_8.000_2005_2016.epw", epw,
                               std::filesystem::copy_options::overwrite_existing);
    std::ofstream(dir + "/jobs.json") << "{\"jobs\": [{\"name\": \"w\", \"render\": " +
                                             quoted({std::string(FEN_SCENES_DIR) + "/room.gltf", "--weather", epw,
                                                     "--weather-hour", "06-21:13", "--paths", "100000", "--width",
                                                     "32", "--no-progress", "--out", dir + "/w.exr"}) +
                                             "}]}";
    auto status = [&] { return nlohmann::json::parse(slurp(dir + "/jobs.summary.json"))["jobs"][0]["status"]; };
    ASSERT_EQ(run("batch " + dir + "/jobs.json").status, 0);
    EXPECT_EQ(status(), "done");
    ASSERT_EQ(run("batch " + dir + "/jobs.json").status, 0);
    EXPECT_EQ(status(), "skipped");
    std::ofstream(epw, std::ios::app) << "\n";
    ASSERT_EQ(run("batch " + dir + "/jobs.json").status, 0);
    EXPECT_EQ(status(), "done");
}

TEST(CliBatch, AnHourlyStudyFromTheWeatherFile)
{
    // scripts/weather_jobs.py writes a job per daylight hour of a day (the sun at least 6 degrees
    // high at mid-hour); the batch renders them all, and its summary gives each hour's mean
    // illuminance on the work plane, highest near noon.
    const std::string dir = test::tempDir("cli-batch-hours");
    const std::string cmd = "cd " + std::string(FEN_SOURCE_DIR) +
                            " && /usr/bin/python3 scripts/weather_jobs.py scenes/weather/tmy_45.000_8.000_2005_2016.epw"
                            " --days 06-21 --out-dir " + dir + "/out --jobs " + dir + "/jobs.json -- scenes/room.gltf"
                            " --no-image --work-plane floor --paths 50000 --no-progress 2>" + dir + "/script.err";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(dir + "/script.err");
    const auto jobs = nlohmann::json::parse(slurp(dir + "/jobs.json"))["jobs"];
    ASSERT_EQ(jobs.size(), 14u);  // 06..19: 05:00-06:00 has the sun below 6 degrees at its middle
    EXPECT_EQ(jobs[0]["name"], "06-21_06");
    // Run where the jobs' relative paths point, as a user would.
    ASSERT_EQ(std::system(("cd " + std::string(FEN_SOURCE_DIR) + " && " + FENESTRA_BIN + " batch " + dir +
                           "/jobs.json 2>" + dir + "/batch.err").c_str()),
              0)
        << slurp(dir + "/batch.err");
    const auto s = nlohmann::json::parse(slurp(dir + "/jobs.summary.json"));
    std::vector<double> lux;
    for (const auto& j : s["jobs"]) {
        EXPECT_EQ(j["status"], "done") << j["name"];
        lux.push_back(j["sensors"]["workplane"]["mean_lux"].get<double>());
    }
    const auto peak = std::max_element(lux.begin(), lux.end()) - lux.begin();
    EXPECT_GE(peak, 5);  // 11:00-12:00 .. 14:00-15:00
    EXPECT_LE(peak, 8);
    EXPECT_GT(lux[static_cast<std::size_t>(peak)], 3.0 * lux.front());
}

TEST(CliBatch, BrokenJobsFilesAreOneLineErrorsNamingTheKey)
{
    const std::string dir = test::tempDir("cli-batch-bad");
    auto jobsFile = [&](const std::string& name, const std::string& text) {
        std::ofstream(dir + "/" + name) << text;
        return dir + "/" + name;
    };
    expectError(run("batch " + dir + "/none.json"), 1, "none.json: cannot open the jobs file");
    expectError(run("batch " + jobsFile("a.json", "{jobs: 1")), 1, "a.json: not JSON");
    expectError(run("batch " + jobsFile("b.json", "{\"jobs\": [], \"x\": 1}")), 1, "b.json: unknown key 'x'");
    expectError(run("batch " + jobsFile("c.json", "{\"jobs\": []}")), 1, "\"jobs\" must be a non-empty array");
    expectError(run("batch " + jobsFile("d.json", "{\"jobs\": [{\"name\": \"a\", \"render\": [\"x\"], \"out\": 1}]}")), 1,
                "d.json: jobs[0]: unknown key 'out'");
    expectError(run("batch " + jobsFile("e.json", "{\"jobs\": [{\"name\": \"a b\", \"render\": [\"x\"]}]}")), 1,
                "jobs[0].name 'a b'");
    expectError(run("batch " + jobsFile("f.json", "{\"jobs\": [{\"name\": \"a\", \"render\": [\"x\"]}, "
                                                  "{\"name\": \"a\", \"render\": [\"y\"]}]}")),
                1, "jobs[1].name 'a': another job has this name");
    expectError(run("batch " + jobsFile("g.json", "{\"jobs\": [{\"name\": \"a\", \"render\": [1]}]}")), 1,
                "jobs[0].render[0]: a string is required");
    // A job's own bad arguments fail that job, with the render's message.
    const CliRun r = run("batch " + jobsFile("h.json", "{\"jobs\": [{\"name\": \"dev\", \"render\": [\"" +
                                                           std::string(FEN_SCENES_DIR) +
                                                           "/room.gltf\", \"--device\", \"0\", \"--out\", \"" + dir +
                                                           "/d.exr\"]}]}"));
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("dev: failed: --device: a batch runs every job on its own device"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace fen
