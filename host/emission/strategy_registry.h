// strategy_registry.h — the emission strategies, each described once (DESIGN.md §3).
//
// A strategy's descriptor says everything the rest of fenestra needs to know about it: its
// --method name, its option block (which registers its command-line options, keeps what was
// given and checks each value's range), its defaults (those of its settings block, and where
// Russian roulette starts), its part of a checkpoint's fingerprint, and its factory. The
// descriptors are defined in the strategies' own files and listed once, in
// strategy_registry.cpp: a new strategy is its own files and one line there; a new option is
// its strategy's files alone.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "emission/strategy.h"

namespace CLI {
class App;
}

namespace fen {

// A strategy's command-line options: registered on the render subcommand, kept as given
// (std::optional: not given), and written over its settings' defaults.
class StrategyOptionBlock {
public:
    virtual ~StrategyOptionBlock() = default;
    virtual void add(CLI::App& render) = 0;
    // Writes what was given into the strategy's block of `settings`, each value checked against
    // its range (one-line fen::Error naming the option, the value and the range). `inUse`: the
    // settings' method is this strategy; an option given to a strategy not in use is an error.
    virtual void apply(EmissionSettings& settings, bool inUse) const = 0;
};

struct StrategyDescriptor {
    EmissionMethod method;
    const char* name;  // --method NAME; the JSON's "method"
    // Where Russian roulette starts unless --roulette-depth is given (docs/results/termination.md).
    int rouletteDepth;
    // Its option block (none: the strategy has no options).
    std::unique_ptr<StrategyOptionBlock> (*options)();
    // Whether, with these settings, it starts paths through the scene's marked portals (--portals).
    bool (*readsPortals)(const EmissionSettings& settings);
    // Its settings that a checkpoint must agree on (render/checkpoint.h).
    nlohmann::json (*fingerprint)(const EmissionSettings& settings);
    std::unique_ptr<EmissionStrategy> (*make)(const EmissionSettings& settings, const EmissionInputs& in);
};

// Every strategy, in the order of their options in the help.
const std::vector<const StrategyDescriptor*>& emissionStrategies();
const StrategyDescriptor& strategyDescriptor(EmissionMethod m);

EmissionMethod parseEmissionMethod(const std::string& s);  // by name; else a one-line error
std::string methodName(EmissionMethod m);
// Where Russian roulette starts for a method when the settings leave it open.
int defaultRouletteDepth(EmissionMethod m);
std::unique_ptr<EmissionStrategy> makeEmissionStrategy(const EmissionSettings& settings, const EmissionInputs& in);

}  // namespace fen
