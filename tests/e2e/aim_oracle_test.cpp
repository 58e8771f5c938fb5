// aim_oracle_test.cpp — scripts/aim_oracle.py, the bound docs/results/guiding.md measures the guide
// against ("Told where the openings are"), stays what it claims: its kernels are edited copies of
// today's kernels/ (patched at anchor lines, so a change there must not leave it silently aiming
// nowhere), they keep the courtyard's mean (the aim is a one-sample mixture with the cosine, the
// weight over the mixture's density: unbiased), and they aim (at the same paths and seed the noise
// is below the learned guide's, which at 2e6 paths has barely begun to steer; both without the
// learned opening aim, which would act before the oracle's); and its bad options are a one-line error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include <nlohmann/json.hpp>

#include "e2e/cli_run.h"
#include "support/gltf_writer.h"

namespace fen {
namespace {

using test::run;
using test::slurp;

TEST(AimOracle, KeepsTheCourtyardsMeanAndAims)
{
    const std::string dir = test::tempDir("aim-oracle");
    const std::string cmd = "cd " + std::string(FEN_SOURCE_DIR) +
                            " && /usr/bin/python3 scripts/aim_oracle.py --targets courtyard --vertices every --out " +
                            dir + "/kernels > " + dir + "/log 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(dir + "/log");
    const std::string render = "render " + std::string(FEN_SCENES_DIR) +
                               "/courtyard.gltf --width 64 --paths 2000000 --seed 1 --adaptive-aim off --no-progress --out " + dir;
    const test::CliRun learned = run(render + "/learned.exr");
    ASSERT_EQ(learned.status, 0) << learned.err;
    const test::CliRun aimed = run(render + "/aimed.exr", "FEN_KERNEL_DIR=" + dir + "/kernels");
    ASSERT_EQ(aimed.status, 0) << aimed.err;
    const auto a = nlohmann::json::parse(slurp(dir + "/learned.json"));
    const auto b = nlohmann::json::parse(slurp(dir + "/aimed.json"));
    const double ma = a["mean_luminance_cd_m2"].get<double>(), mb = b["mean_luminance_cd_m2"].get<double>();
    const double sa = a["mean_std_err_cd_m2"].get<double>(), sb = b["mean_std_err_cd_m2"].get<double>();
    // 4 sigma of the difference of two independent estimates
    EXPECT_LT(std::abs(ma - mb), 4.0 * std::sqrt(sa * sa + sb * sb)) << ma << " against " << mb;
    EXPECT_LT(b["noise_std_err_cd_m2"].get<double>(), a["noise_std_err_cd_m2"].get<double>());
    EXPECT_GT(b["counters"]["guided_vertices"].get<double>(), 0.0);
}

TEST(AimOracle, BadOptionsAreOneLine)
{
    const std::string dir = test::tempDir("aim-oracle-bad");
    for (const std::string& args : {std::string("--targets courtyard --weights 1,2"),
                                    std::string("--targets courtyard --weights x"),
                                    std::string("--targets courtyard --share 1")}) {
        const std::string cmd = "cd " + std::string(FEN_SOURCE_DIR) + " && /usr/bin/python3 scripts/aim_oracle.py " +
                                args + " --out " + dir + "/k > " + dir + "/log 2>&1";
        const int status = std::system(cmd.c_str());
        EXPECT_NE(status, 0) << args;
        const std::string log = slurp(dir + "/log");
        EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 1) << log;
        EXPECT_NE(log.find("aim_oracle.py: --"), std::string::npos) << log;
    }
}

}  // namespace
}  // namespace fen
