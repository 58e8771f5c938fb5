// cli_run.h — running the fenestra binary as a user does, for the e2e tests: its exit status,
// stdout and stderr, and the check every failure passes (one line on stderr, starting
// "fenestra: error:", naming what is at fault, the expected exit status).
#pragma once

#include <string>

namespace fen { namespace test {

struct CliRun {
    int status = -1;  // exit code; 128+signal if killed
    std::string out, err;
};

// The whole file, "" if it cannot be read.
std::string slurp(const std::string& path);

// `fenestra ARGS` through the shell (ARGS as typed on a command line), with `env` (NAME=VALUE ...)
// before it.
CliRun run(const std::string& args, const std::string& env = "");

// One line, the project's prefix, the expected fragment, the expected status.
void expectError(const CliRun& r, int status, const std::string& fragment);

} }  // namespace fen::test
