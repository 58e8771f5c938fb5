// team_test.cpp — `mpirun -np N fenestra render` and `--device all` as a user runs them
// (host/team/; DESIGN.md §9):
// the ranks share every pass's paths, and the outputs are the bytes one process writes, for each
// emission method (adaptive with its learning passes) and with sensor cells, and for an annual
// study's daylight coefficients; a render stopped by
// SIGTERM on every rank (what a batch scheduler sends) leaves a checkpoint that another number of
// ranks resumes to the same bytes; a killed rank ends the job with an error in bounded time; a
// batch's jobs spread over ranks write what one process writes, and a rerun skips them; only
// `render` and `batch` run under mpirun; two devices of one process write the bytes of one. Ranks and
// devices are oversubscribed on the CI's 2 cores.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "e2e/cli_run.h"
#include "support/gltf_writer.h"

namespace fen {
namespace {

using test::CliRun;
using test::run;
using test::slurp;

// Two PoCL devices (POCL_DEVICES makes two of the CPU): `--device all` shares the paths between
// them, and the bytes are those of one; a list naming a device twice is refused in one line. Where
// the machine's OpenCL shows one device even so (a GPU's driver alone, or a PoCL that names its
// CPU device otherwise), there is no second device to share with, and the test says so.
TEST(TeamDevices, TwoDevicesOfOneProcessWriteTheBytesOfOne)
{
    const std::string dir = test::tempDir("team-devices");
    const std::string scene = std::string(FEN_SCENES_DIR) + "/room.gltf";
    const std::string env = "POCL_DEVICES='pthread pthread'";
    const CliRun devices = run("devices --json", env);
    ASSERT_EQ(devices.status, 0) << devices.err;
    if (nlohmann::json::parse(devices.out).size() < 2)
        GTEST_SKIP() << "one OpenCL device here, with " << env << ":\n" << devices.out;
    const std::string args = " --method adaptive --paths 400000 --batches 4 --width 48 --seed 3 --work-plane floor "
                             "--no-progress";
    const CliRun one = run("render " + scene + " --out " + dir + "/one.exr --device 0" + args, env);
    ASSERT_EQ(one.status, 0) << one.err;
    const CliRun two = run("render " + scene + " --out " + dir + "/two.exr --device all" + args, env);
    ASSERT_EQ(two.status, 0) << two.err;
    EXPECT_EQ(slurp(dir + "/two.exr"), slurp(dir + "/one.exr"));
    EXPECT_EQ(slurp(dir + "/two.noise.exr"), slurp(dir + "/one.noise.exr"));
    EXPECT_EQ(slurp(dir + "/two.sensors.csv"), slurp(dir + "/one.sensors.csv"));
    const auto j = nlohmann::json::parse(slurp(dir + "/two.json"));
    EXPECT_EQ(j["team"]["members"], 2);
    EXPECT_EQ(j["team"]["kind"], "2 devices");
    EXPECT_EQ(j["counters"], nlohmann::json::parse(slurp(dir + "/one.json"))["counters"]);
    EXPECT_NE(j["device"].get<std::string>().find(" + "), std::string::npos);
    test::expectError(run("render " + scene + " --out " + dir + "/x.exr --device 0,0" + args, env), 1,
                      "is named twice");
}

#ifdef FEN_HAVE_MPI

// mpirun as root, with more ranks than cores; the tests' environment reaches the ranks.
std::string mpirun(int ranks)
{
    return "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 "
           "mpirun --oversubscribe -np " + std::to_string(ranks);
}

const std::string kRoom = std::string(FEN_SCENES_DIR) + "/room.gltf";

class TeamMethods : public ::testing::TestWithParam<const char*> {};

TEST_P(TeamMethods, OneTwoAndThreeRanksWriteTheBytesOfOneProcess)
{
    // 4 batches of 100 000 paths: adaptive emission learns in passes of 65 536 doubling, so
    // passes cross batch ends and the members' statistics are summed mid-batch too.
    const std::string dir = test::tempDir("team-method");
    const std::string args = " " + std::string(GetParam()) +
                             " --paths 400000 --batches 4 --width 48 --seed 3 --work-plane floor --no-progress";
    const CliRun one = run("render " + kRoom + " --out " + dir + "/one.exr" + args);
    ASSERT_EQ(one.status, 0) << one.err;
    const std::string image = slurp(dir + "/one.exr"), noise = slurp(dir + "/one.noise.exr"),
                      cells = slurp(dir + "/one.sensors.csv");
    ASSERT_FALSE(image.empty());
    ASSERT_FALSE(cells.empty());
    for (int ranks : {1, 2, 3}) {
        const std::string out = dir + "/np" + std::to_string(ranks);
        const CliRun r = run("render " + kRoom + " --out " + out + ".exr" + args, mpirun(ranks));
        ASSERT_EQ(r.status, 0) << ranks << " ranks: " << r.err;
        EXPECT_EQ(slurp(out + ".exr"), image) << ranks << " ranks";
        EXPECT_EQ(slurp(out + ".noise.exr"), noise) << ranks << " ranks";
        EXPECT_EQ(slurp(out + ".sensors.csv"), cells) << ranks << " ranks";
        const auto j = nlohmann::json::parse(slurp(out + ".json"));
        const auto plain = nlohmann::json::parse(slurp(dir + "/one.json"));
        // the counters are the team's sums: those of one process
        EXPECT_EQ(j["counters"], plain["counters"]) << ranks << " ranks";
        if (ranks > 1) {
            EXPECT_EQ(j["team"]["members"], ranks);
            EXPECT_GT(j["team"]["reductions"].get<int>(), 0);
            EXPECT_GT(j["team"]["bytes"].get<double>(), 0.0);
        } else {
            EXPECT_FALSE(j.contains("team"));
        }
    }
}

// The relative target steers by pixel: the film is summed after every pass, not once a batch.
INSTANTIATE_TEST_SUITE_P(Methods, TeamMethods,
                         ::testing::Values("--method uniform", "--method portal", "--method adaptive",
                                           "--method adaptive --adaptive-target relative"));

TEST(Team, AnAnnualStudyWritesTheBytesOfOneProcess)
{
    // the daylight-coefficient matrices are summed like the cells (sensor/device_sensors.h)
    const std::string dir = test::tempDir("team-annual");
    const std::string args = " --annual " + std::string(FEN_SCENES_DIR) +
                             "/weather/tmy_45.000_8.000_2005_2016.epw --work-plane floor --paths 400000 --batches 4 "
                             "--no-progress";
    ASSERT_EQ(run("render " + kRoom + " --out " + dir + "/one" + args).status, 0);
    const CliRun r = run("render " + kRoom + " --out " + dir + "/two" + args, mpirun(2));
    ASSERT_EQ(r.status, 0) << r.err;
    for (const char* file : {".annual.csv", ".dc.mtx", ".dc-direct.mtx", ".sensors.csv"}) {
        EXPECT_FALSE(slurp(dir + "/one" + file).empty()) << file;
        EXPECT_EQ(slurp(dir + "/two" + file), slurp(dir + "/one" + file)) << file;
    }
}

TEST(Team, AStoppedTeamResumesWithAnotherNumberOfRanksToTheSameBytes)
{
    // SIGTERM to every rank stops the team at the batch in flight; the root writes the
    // checkpoint; three ranks resume it, and the image is the uninterrupted one's. The stop comes
    // a second of MPI start-up plus a third of the way into the uninterrupted render's time, after
    // its set-up less its kernel build (both from its JSON; the team finds the kernels in the cache
    // that run filled), so that it falls inside the team's render on a slow machine as on a fast one.
    const std::string dir = test::tempDir("team-resume");
    const std::string args = " --paths 8388608 --batches 64 --width 32 --seed 9 --no-progress --method adaptive";
    const CliRun whole = run("render " + kRoom + " --out " + dir + "/whole.exr" + args);
    ASSERT_EQ(whole.status, 0) << whole.err;
    const auto wj = nlohmann::json::parse(slurp(dir + "/whole.json"));
    const double render = wj["seconds"]["render"].get<double>();
    const double stopAt =
        wj["seconds"]["total"].get<double>() - render - wj["seconds"]["kernel_build"].get<double>() + 1.0 + render / 3.0;
    char sleep[32];
    std::snprintf(sleep, sizeof sleep, "%.2f", stopAt);
    const std::string cmd = mpirun(2) + " " + FENESTRA_BIN + " render " + kRoom + " --out " + dir + "/r.exr" + args +
                            " --checkpoint " + dir + "/c.ckpt 2>" + dir + "/err & pid=$!; sleep " + sleep + "; "
                            "pkill -TERM -f \"^" + FENESTRA_BIN + " render .*r.exr\"; wait $pid; echo $? >" + dir + "/status";
    ASSERT_EQ(std::system(("bash -c '" + cmd + "'").c_str()), 0);
    EXPECT_NE(std::stoi(slurp(dir + "/status")), 0) << slurp(dir + "/err");
    ASSERT_FALSE(slurp(dir + "/c.ckpt").empty()) << slurp(dir + "/err");
    // the stopped team's outputs are whole: the image of the batches it finished
    const auto stopped = nlohmann::json::parse(slurp(dir + "/r.json"));
    EXPECT_TRUE(stopped["interrupted"].get<bool>());
    EXPECT_GT(stopped["batches"].get<int>(), 0);
    EXPECT_FALSE(slurp(dir + "/r.exr").empty());
    // every rank got the signal; one line says so (the root's)
    const std::string err = slurp(dir + "/err");
    const std::string said = "fenestra: interrupted: finishing the paths in flight";
    const std::size_t first = err.find(said);
    EXPECT_NE(first, std::string::npos) << err;
    EXPECT_EQ(err.find(said, first + 1), std::string::npos) << err;
    const CliRun r = run("render " + kRoom + " --out " + dir + "/r.exr" + args + " --resume " + dir + "/c.ckpt", mpirun(3));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(slurp(dir + "/r.exr"), slurp(dir + "/whole.exr"));
    const auto j = nlohmann::json::parse(slurp(dir + "/r.json"));
    EXPECT_GT(j["checkpoint"]["resumed_batches"].get<int>(), 0);
    EXPECT_LT(j["checkpoint"]["resumed_batches"].get<int>(), 64);
}

TEST(Team, AKilledRankEndsTheJobWithAnErrorInBoundedTime)
{
    // A minute's render; one rank killed 5 s in. The job must end well before the minute, with a
    // non-zero status and a message naming what failed -- not hang in a collective.
    const std::string dir = test::tempDir("team-kill");
    const std::string tag = dir + "/k.exr";
    const auto t0 = std::chrono::steady_clock::now();
    const std::string cmd = mpirun(2) + " " + FENESTRA_BIN + " render " + kRoom + " --out " + tag +
                            " --time 60 --width 32 --no-progress >/dev/null 2>" + dir + "/err & pid=$!; sleep 5; "
                            "pkill -KILL -n -f \"^" + FENESTRA_BIN + " render .*" + tag + "\"; wait $pid; echo $? >" + dir + "/status";
    ASSERT_EQ(std::system(("bash -c '" + cmd + "'").c_str()), 0);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_NE(std::stoi(slurp(dir + "/status")), 0);
    EXPECT_LT(seconds, 40.0);
    EXPECT_NE(slurp(dir + "/err").find("signal 9"), std::string::npos) << slurp(dir + "/err");
}

TEST(Team, ATimedRenderEndsByTheRootsClock)
{
    // --time: the calibration, the batch size and the end are rank 0's decisions, so every rank
    // stops after the same batch and the job ends near the budget
    const std::string dir = test::tempDir("team-time");
    const auto t0 = std::chrono::steady_clock::now();
    const CliRun r = run("render " + kRoom + " --out " + dir + "/t.exr --time 4 --width 32 --no-progress", mpirun(2));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_LT(seconds, 30.0);
    const auto j = nlohmann::json::parse(slurp(dir + "/t.json"));
    EXPECT_GE(j["batches"].get<int>(), 2);
    EXPECT_EQ(j["team"]["members"], 2);
    EXPECT_GT(j["seconds"]["calibration"].get<double>(), 0.0);
}

TEST(Team, ABatchKilledUnderMpirunKeepsTheJobsItFinished)
{
    // Two quick jobs and a minute-long one on two ranks, every rank killed 10 s in: the quick
    // jobs' shards survive, and a rerun skips them.
    const std::string dir = test::tempDir("team-batch-kill");
    const auto job = [&](const std::string& name, const std::string& budget) {
        return "{\"name\": \"" + name + "\", \"render\": [\"" + kRoom + "\", " + budget +
               ", \"--width\", \"32\", \"--no-progress\", \"--out\", \"" + dir + "/" + name + ".exr\"]}";
    };
    std::ofstream(dir + "/jobs.json") << "{\"jobs\": [" << job("a", "\"--paths\", \"100000\"") << ", "
                                      << job("b", "\"--paths\", \"100000\"") << ", "
                                      << job("long", "\"--time\", \"60\"") << "]}";
    const std::string cmd = mpirun(2) + " " + FENESTRA_BIN + " batch " + dir + "/jobs.json >/dev/null 2>" + dir +
                            "/err & pid=$!; sleep 10; pkill -KILL -f \"^" + FENESTRA_BIN + " batch " + dir +
                            "\"; wait $pid; true";
    ASSERT_EQ(std::system(("bash -c '" + cmd + "'").c_str()), 0);
    EXPECT_FALSE(slurp(dir + "/a.exr").empty()) << slurp(dir + "/err");
    EXPECT_FALSE(slurp(dir + "/b.exr").empty()) << slurp(dir + "/err");
    // the rerun, as one process, without the long job's minute: the quick jobs are skipped
    std::ofstream(dir + "/jobs.json") << "{\"jobs\": [" << job("a", "\"--paths\", \"100000\"") << ", "
                                      << job("b", "\"--paths\", \"100000\"") << ", "
                                      << job("long", "\"--paths\", \"1000\"") << "]}";
    const CliRun again = run("batch " + dir + "/jobs.json");
    ASSERT_EQ(again.status, 0) << again.err;
    const auto summary = nlohmann::json::parse(slurp(dir + "/jobs.summary.json"));
    EXPECT_EQ(summary["jobs"][0]["status"], "skipped");
    EXPECT_EQ(summary["jobs"][1]["status"], "skipped");
    EXPECT_EQ(summary["jobs"][2]["status"], "done");
    EXPECT_TRUE(slurp(dir + "/jobs.state.rank0.json").empty());  // folded into the state
    EXPECT_TRUE(slurp(dir + "/jobs.state.rank1.json").empty());
}

TEST(Team, RanksThatRenderDifferentThingsAreAnErrorNamingTheDifference)
{
    // mpirun's MPMD form starts the two ranks with other seeds: an error naming the seed, not a
    // hang or an image of neither
    const std::string dir = test::tempDir("team-mismatch");
    const std::string args = "render " + kRoom + " --out " + dir + "/m.exr --paths 100000 --width 32 --no-progress";
    const CliRun r = run(args + " --seed 2", mpirun(1) + " " + FENESTRA_BIN + " " + args + " --seed 1 : -np 1");
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("fenestra: error: rank 1: this member's render differs from rank 0's in its seed"),
              std::string::npos)
        << r.err;
}

TEST(Team, OnlyRenderAndBatchRunUnderMpirun)
{
    const CliRun r = run("devices", mpirun(2));
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("fenestra: error: under mpirun only `fenestra render` and `fenestra batch` share"),
              std::string::npos)
        << r.err;
}

TEST(Team, ABatchSpreadOverRanksWritesWhatOneProcessWrites)
{
    // Three ranks take five jobs as they come free: every job's image is the bytes the batch of
    // one process writes, the failing job is reported in the summary, and a rerun under mpirun
    // skips what the first run finished (rank 0 wrote the state once it had every outcome).
    const std::string dir = test::tempDir("team-batch");
    const auto jobsFile = [&](const std::string& tag) {
        std::string text = "{\"jobs\": [";
        for (int k = 0; k < 5; ++k) {
            const std::string scene = k == 3 ? dir + "/none.gltf" : kRoom;
            text += std::string(k ? ", " : "") + "{\"name\": \"j" + std::to_string(k) + "\", \"render\": [\"" + scene +
                    "\", \"--paths\", \"200000\", \"--width\", \"32\", \"--seed\", \"" + std::to_string(k + 1) +
                    "\", \"--no-progress\", \"--out\", \"" + dir + "/" + tag + "_j" + std::to_string(k) + ".exr\"]}";
        }
        std::ofstream(dir + "/" + tag + ".json") << text << "]}";
        return dir + "/" + tag + ".json";
    };
    const CliRun one = run("batch " + jobsFile("one"));
    EXPECT_EQ(one.status, 1) << one.err;
    const CliRun three = run("batch " + jobsFile("three"), mpirun(3));
    EXPECT_NE(three.status, 0) << three.err;  // one job failed
    for (int k : {0, 1, 2, 4}) {
        const std::string a = slurp(dir + "/one_j" + std::to_string(k) + ".exr");
        EXPECT_FALSE(a.empty()) << k;
        EXPECT_EQ(slurp(dir + "/three_j" + std::to_string(k) + ".exr"), a) << "job " << k;
    }
    const auto summary = nlohmann::json::parse(slurp(dir + "/three.summary.json"));
    ASSERT_EQ(summary["jobs"].size(), 5u);
    EXPECT_EQ(summary["failed"], 1);
    EXPECT_EQ(summary["jobs"][3]["status"], "failed");
    EXPECT_NE(summary["jobs"][3]["error"].get<std::string>().find("none.gltf"), std::string::npos);
    for (int k : {0, 1, 2, 4})
        EXPECT_EQ(summary["jobs"][k]["status"], "done") << k;
    run("batch " + dir + "/three.json", mpirun(2));
    const auto again = nlohmann::json::parse(slurp(dir + "/three.summary.json"));
    for (int k : {0, 1, 2, 4})
        EXPECT_EQ(again["jobs"][k]["status"], "skipped") << k;
    EXPECT_EQ(again["jobs"][3]["status"], "failed");
}

#else

TEST(Team, BuiltWithoutMpi) { GTEST_SKIP() << "built without MPI: mpirun renders are not part of this build"; }

#endif

}  // namespace
}  // namespace fen
