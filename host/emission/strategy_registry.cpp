// strategy_registry.cpp — the one list of emission strategies, and lookups in it
// (strategy_registry.h).
#include "emission/strategy_registry.h"

#include "emission/adaptive_strategy.h"
#include "emission/portal_strategy.h"
#include "emission/uniform_strategy.h"
#include "util/error.h"

namespace fen {

const std::vector<const StrategyDescriptor*>& emissionStrategies()
{
    static const std::vector<const StrategyDescriptor*> all = {
        &kUniformStrategy,
        &kPortalStrategy,
        &kAdaptiveStrategy,
    };
    return all;
}

const StrategyDescriptor& strategyDescriptor(EmissionMethod m)
{
    for (const StrategyDescriptor* d : emissionStrategies())
        if (d->method == m)
            return *d;
    throw Error("unknown emission method");
}

EmissionMethod parseEmissionMethod(const std::string& s)
{
    std::string names;
    const auto& all = emissionStrategies();
    for (std::size_t i = 0; i < all.size(); ++i) {
        if (s == all[i]->name)
            return all[i]->method;
        names += cat(i == 0 ? "" : i + 1 == all.size() ? " or " : ", ", all[i]->name);
    }
    throw Error(cat("--method '", printable(s, 40), "': expected ", names));
}

std::string methodName(EmissionMethod m) { return strategyDescriptor(m).name; }

int defaultRouletteDepth(EmissionMethod m) { return strategyDescriptor(m).rouletteDepth; }

std::unique_ptr<EmissionStrategy> makeEmissionStrategy(const EmissionSettings& settings, const EmissionInputs& in)
{
    return strategyDescriptor(settings.method).make(settings, in);
}

}  // namespace fen
