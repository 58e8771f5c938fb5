// commands.h — the subcommands of the fenestra CLI (host/main.cpp parses, these run).
#pragma once

#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace fen {

int runDevices(bool json);

// `fenestra falsecolor INPUT --out OUT.png [...]` (falsecolor_cmd.cpp; docs/false_color.md).
struct FalseColorOptions {
    std::string input, out;
    bool log = false, linear = false;      // neither: log for an image, linear for a sensor file
    std::optional<double> min, max;        // not given: fitted to the data (io/false_color.h)
    std::optional<int> steps;              // not given: 8, or on a scale of whole decades a multiple of them
    std::optional<std::string> quantity;   // illuminance (default) | df; sensor files only
    std::optional<std::string> title;      // not given: what and where (the file, the sensor)
};
void addFalseColorOptions(CLI::App& sub, FalseColorOptions& o);
int runFalseColor(const FalseColorOptions& o);

}  // namespace fen
