// portal_options.h — the `portal` strategy's settings and command-line options (DESIGN.md §3.2):
// its option block (--portal-overlap, --portal-complement), their defaults, ranges and help, and
// its part of a checkpoint's fingerprint. The marking itself (--portals) is the scene's, read by
// every strategy that starts paths through portals (emission/emission_options.h).
#pragma once

#include <memory>

#include <nlohmann/json.hpp>

#include "emission/portal_emission.h"

namespace fen {

struct EmissionSettings;
class StrategyOptionBlock;

struct PortalOptions {
    // Where portals overlap along a line: rejection (the paper's fix) or weighting; `none` is
    // biased, for demonstration (portal_emission.h).
    PortalOverlap overlap = PortalOverlap::Reject;
    // The share of paths that estimate the light no portal passes (0: the paper's method alone,
    // no estimate; portal_strategy.h).
    double complement = 0.05;
};

// The ranges, checked before anything is built (fen::Error naming the option, value and range).
void validatePortalOptions(const PortalOptions& o);

// The command-line block (emission/strategy_registry.h).
std::unique_ptr<StrategyOptionBlock> makePortalOptionBlock();

// What a checkpoint must agree on (render/checkpoint.h).
nlohmann::json portalFingerprint(const EmissionSettings& e);

}  // namespace fen
