// cli_run.cpp — running the fenestra binary for the e2e tests (cli_run.h).
#include "e2e/cli_run.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

#include "support/gltf_writer.h"

namespace fen { namespace test {

std::string slurp(const std::string& path)
{
    std::ifstream f(path);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

CliRun run(const std::string& args, const std::string& env)
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

void expectError(const CliRun& r, int status, const std::string& fragment)
{
    EXPECT_EQ(r.status, status) << r.err;
    EXPECT_EQ(r.err.rfind("fenestra: error: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "not one line: " << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
}

} }  // namespace fen::test
