// emission_options.cpp — --method, --portals and the strategies' option blocks
// (emission_options.h).
#include "emission/emission_options.h"

#include <CLI/CLI.hpp>

#include "emission/strategy_registry.h"
#include "util/error.h"

namespace fen {

EmissionOptions::EmissionOptions()
{
    for (const StrategyDescriptor* d : emissionStrategies())
        blocks_.push_back(d->options ? d->options() : nullptr);
}

EmissionOptions::~EmissionOptions() = default;
EmissionOptions::EmissionOptions(EmissionOptions&&) noexcept = default;
EmissionOptions& EmissionOptions::operator=(EmissionOptions&&) noexcept = default;

void EmissionOptions::add(CLI::App& render)
{
    // "adaptive (default), uniform or portal": the default first, then the others as listed.
    std::vector<std::string> names = {method_ + " (default)"};
    for (const StrategyDescriptor* d : emissionStrategies())
        if (d->name != method_)
            names.push_back(d->name);
    std::string list;
    for (std::size_t i = 0; i < names.size(); ++i)
        list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    render.add_option("--method", method_, "Emission strategy: " + list);
    render.add_option("--portals", portals_, "Portal nodes NAME,NAME replacing the scene's extras.portal marking");
    for (const auto& block : blocks_)
        if (block)
            block->add(render);
}

EmissionSettings EmissionOptions::settings() const
{
    EmissionSettings e;
    e.method = parseEmissionMethod(method_);
    e.portals = portals_.value_or("");
    const auto& all = emissionStrategies();
    for (std::size_t i = 0; i < all.size(); ++i)
        if (blocks_[i])
            blocks_[i]->apply(e, all[i]->method == e.method);
    if (portals_ && !strategyDescriptor(e.method).readsPortals(e))
        throw Error("--portals applies to --method portal and to --method adaptive --base portal");
    return e;
}

}  // namespace fen
