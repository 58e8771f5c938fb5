// emission_options.h — the render command's emission options (DESIGN.md §3): --method, the
// scene's portal marking --portals, and the option block of every registered strategy
// (strategy_registry.h), resolved into the EmissionSettings of a render.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "emission/strategy.h"

namespace CLI {
class App;
}

namespace fen {

class StrategyOptionBlock;

class EmissionOptions {
public:
    EmissionOptions();
    ~EmissionOptions();
    EmissionOptions(EmissionOptions&&) noexcept;
    EmissionOptions& operator=(EmissionOptions&&) noexcept;

    // Registers --method, --portals and every strategy's options on the render subcommand.
    void add(CLI::App& render);
    // The settings asked for: every strategy's defaults, overwritten by what was given. Options
    // of a strategy not in use and values out of range are one-line errors naming the option.
    EmissionSettings settings() const;

private:
    // adaptive: unbiased without marking, and the most efficient on every shipped scene
    // (README "Which method when", docs/results/).
    std::string method_ = "adaptive";
    std::optional<std::string> portals_;  // node names replacing the scene's marking
    std::vector<std::unique_ptr<StrategyOptionBlock>> blocks_;  // per strategy; null: no options
};

}  // namespace fen
