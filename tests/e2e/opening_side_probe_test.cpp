// opening_side_probe_test.cpp — scripts/opening_side_probe.py, the probe docs/results/guiding.md
// measures ("Light reflected outside, estimated from the openings' side"), stays what it claims:
// its kernels are edited copies of today's kernels/ (patched at anchor lines, so a change there must
// not leave it silently estimating nothing); the image keeps the courtyard's mean (the two parts
// are disjoint and each unbiased); the openings' part carries the light the courtyard gets by
// bouncing outside, which the light paths then no longer deliver; and its bad options are a
// one-line error. Its speed is a benchmark, not a test (guiding.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include <nlohmann/json.hpp>

#include "e2e/cli_run.h"
#include "support/gltf_writer.h" // test::tempDir

namespace fen {
namespace {

using test::run;
using test::slurp;

std::string writeProbe(const std::string& dir, const std::string& args)
{
    const std::string out = dir + "/kernels-" + std::to_string(std::hash<std::string>{}(args));
    const std::string cmd = "cd " + std::string(FEN_SOURCE_DIR) + " && /usr/bin/python3 scripts/opening_side_probe.py " +
                            args + " --out " + out + " > " + dir + "/log 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << slurp(dir + "/log");
    return out;
}

TEST(OpeningSideProbe, KeepsTheCourtyardsMeanAndTheOpeningsCarryWhatBouncedOutside)
{
    const std::string dir = test::tempDir("opening-side-probe");
    const std::string both = writeProbe(dir, "--share 0.5");
    const std::string lines = writeProbe(dir, "--share 0.5 --part lines");
    const std::string render = "render " + std::string(FEN_SCENES_DIR) +
                               "/courtyard.gltf --width 64 --paths 4000000 --seed 1 --kernels fused --no-progress --out " +
                               dir;
    const test::CliRun today = run(render + "/today.exr");
    ASSERT_EQ(today.status, 0) << today.err;
    const test::CliRun probe = run(render + "/both.exr", "FEN_KERNEL_DIR=" + both);
    ASSERT_EQ(probe.status, 0) << probe.err;
    const test::CliRun rest = run(render + "/lines.exr", "FEN_KERNEL_DIR=" + lines);
    ASSERT_EQ(rest.status, 0) << rest.err;
    const auto a = nlohmann::json::parse(slurp(dir + "/today.json"));
    const auto b = nlohmann::json::parse(slurp(dir + "/both.json"));
    const auto c = nlohmann::json::parse(slurp(dir + "/lines.json"));
    const double ma = a["mean_luminance_cd_m2"].get<double>(), mb = b["mean_luminance_cd_m2"].get<double>();
    const double sa = a["mean_std_err_cd_m2"].get<double>(), sb = b["mean_std_err_cd_m2"].get<double>();
    // 4 sigma of the difference of two independent estimates
    EXPECT_LT(std::abs(ma - mb), 4.0 * std::sqrt(sa * sa + sb * sb)) << ma << " against " << mb;
    // the courtyard's window sees no sun: the light paths keep only what glass reflected outside
    // (0.25 cd/m2 of 452 at 20 s, guiding.md); were the light that bounced outside counted by both
    // parts, or by neither, the means above would part
    EXPECT_LT(c["mean_luminance_cd_m2"].get<double>(), 0.05 * mb);
    EXPECT_GT(b["counters"]["diffuse_vertices"].get<double>(), 0.0);
}

TEST(OpeningSideProbe, BadOptionsAreOneLine)
{
    const std::string dir = test::tempDir("opening-side-probe-bad");
    for (const std::string& args : {std::string("--share 1"), std::string("--share 0"), std::string("--share -0.5")}) {
        const std::string cmd = "cd " + std::string(FEN_SOURCE_DIR) + " && /usr/bin/python3 scripts/opening_side_probe.py " +
                                args + " --out " + dir + "/k > " + dir + "/log 2>&1";
        const int status = std::system(cmd.c_str());
        EXPECT_NE(status, 0) << args;
        const std::string log = slurp(dir + "/log");
        EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 1) << log;
        EXPECT_NE(log.find("opening_side_probe.py: --share"), std::string::npos) << log;
    }
}

}  // namespace
}  // namespace fen
