// cli_test.cpp — the fenestra binary as a user meets it: bad input gives one line on stderr,
// starting "fenestra: error:", naming the file/option at fault, and a non-zero exit; never a
// crash. Plus a smoke run of `devices` and `bench --json`.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

#include <nlohmann/json.hpp>

#include "support/gltf_writer.h"

namespace fen {
namespace {

struct CliRun {
    int status = -1;  // exit code; 128+signal if killed
    std::string out, err;
};

std::string slurp(const std::string& path)
{
    std::ifstream f(path);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

CliRun run(const std::string& args, const std::string& env = "")
{
    static const std::string dir = test::tempDir("cli");
    static int counter = 0;
    const std::string out = dir + "/out" + std::to_string(counter), err = dir + "/err" + std::to_string(counter);
    ++counter;
    const std::string cmd = env + " " + FENESTRA_BIN + " " + args + " >" + out + " 2>" + err;
    const int raw = std::system(cmd.c_str());
    CliRun r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
    r.out = slurp(out);
    r.err = slurp(err);
    return r;
}

// One line, the project's prefix, the expected fragment, the expected status.
void expectError(const CliRun& r, int status, const std::string& fragment)
{
    EXPECT_EQ(r.status, status) << r.err;
    EXPECT_EQ(r.err.rfind("fenestra: error: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "not one line: " << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
}

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
        }
    }
    EXPECT_GT(j["scene"]["triangles"].get<int>(), 100000);
}

}  // namespace
}  // namespace fen
