// strategy.cpp — choosing an emission strategy by name (strategy.h).
#include "emission/strategy.h"

#include "emission/adaptive_strategy.h"
#include "emission/portal_strategy.h"
#include "emission/uniform_strategy.h"
#include "util/error.h"

namespace fen {

EmissionMethod parseEmissionMethod(const std::string& s)
{
    if (s == "uniform")
        return EmissionMethod::Uniform;
    if (s == "portal")
        return EmissionMethod::Portal;
    if (s == "adaptive")
        return EmissionMethod::Adaptive;
    throw Error(cat("--method '", s, "': expected uniform, portal or adaptive"));
}

std::string methodName(EmissionMethod m)
{
    switch (m) {
    case EmissionMethod::Uniform: return "uniform";
    case EmissionMethod::Portal: return "portal";
    case EmissionMethod::Adaptive: return "adaptive";
    }
    return "?";
}

std::unique_ptr<EmissionStrategy> makeEmissionStrategy(const EmissionSettings& settings,
                                                       const EmissionInputs& in)
{
    switch (settings.method) {
    case EmissionMethod::Uniform: return makeUniformStrategy(in);
    case EmissionMethod::Portal: return makePortalStrategy(settings, in);
    case EmissionMethod::Adaptive: return makeAdaptiveStrategy(settings, in);
    }
    throw Error("unknown emission method");
}

}  // namespace fen
