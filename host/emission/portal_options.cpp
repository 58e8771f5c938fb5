// portal_options.cpp — the `portal` strategy's option block, ranges and fingerprint
// (portal_options.h).
#include "emission/portal_options.h"

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "emission/strategy_registry.h"
#include "util/error.h"

namespace fen {

namespace {

class PortalOptionBlock final : public StrategyOptionBlock {
public:
    void add(CLI::App& render) override
    {
        render.add_option("--portal-complement", complement_,
                          "With portal: share of paths that measure the light no portal passes (default 0.05; 0: none)");
        render.add_option("--portal-overlap", overlap_,
                          "With portal: where portals overlap along a ray, reject (default) or weight; none is "
                          "biased (for demonstration)");
    }

    void apply(EmissionSettings& e, bool inUse) const override
    {
        PortalOptions& p = e.portal;
        if (overlap_)
            p.overlap = parsePortalOverlap(*overlap_);
        if (!inUse && overlap_)
            throw Error("--portal-overlap applies to --method portal");
        if (!inUse && complement_)
            throw Error("--portal-complement applies to --method portal");
        if (complement_)
            p.complement = *complement_;
        if (inUse)
            validatePortalOptions(p);
    }

private:
    std::optional<std::string> overlap_;
    std::optional<double> complement_;
};

}  // namespace

void validatePortalOptions(const PortalOptions& o)
{
    if (!(o.complement >= 0.0 && o.complement <= 0.5))
        throw Error(cat("--portal-complement ", o.complement, ": must be in [0, 0.5]"));
}

std::unique_ptr<StrategyOptionBlock> makePortalOptionBlock() { return std::make_unique<PortalOptionBlock>(); }

nlohmann::json portalFingerprint(const EmissionSettings& e)
{
    return {{"overlap", static_cast<int>(e.portal.overlap)}, {"complement", e.portal.complement}};
}

}  // namespace fen
