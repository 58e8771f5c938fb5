// adaptive_options.h — the `adaptive` strategy's settings and command-line options (DESIGN.md
// §3.3, §3.4): its option block (--base, --adaptive-*), their defaults, ranges and help, and its
// part of a checkpoint's fingerprint. Defaults and the measurements behind them:
// docs/results/adaptive.md, docs/results/guide.md.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "emission/adaptive_grid.h"
#include "emission/emission_method.h"
#include "scatter/first_bounce_guide.h"
#include "scatter/opening_aim.h"

namespace fen {

struct EmissionSettings;
class StrategyOptionBlock;

struct AdaptiveOptions {
    EmissionMethod base = EmissionMethod::Uniform;  // Uniform or Portal
    int initialDepth = 3;      // origins: every region starts as 4^depth boxes ...
    int maxDepth = 10;         // ... split down to 2^-depth of the region's side
    int initialSkyDepth = 1;   // sky directions: 4^depth boxes of (1 - cos(theta), phi / 2 pi) ...
    int maxSkyDepth = 6;       // ... split down to 2^-depth of each side
    GridEstimate estimate = GridEstimate::Larger;  // how <sum Lambda^2> is estimated per cell
    double defensive = 0.1;    // share of the base density in the mixture (alpha)
    double diskShare = 0.1;    // over a portal base: the disk's share of the base density (beta)
    double splitGain = 1.0 / 2048.0;  // split a cell when that lowers the learned objective this much
    double priorPaths = 32.0;  // pseudo-paths of the prior in every cell
    bool weighBatches = true;  // batches weigh by predicted precision (else all alike)
    // What the learned density minimises: the image's squared error (the paper's eq. 7), or its
    // relative squared error -- each contribution measured against its pixel's brightness, so
    // that a bright sun patch does not draw the paths away from the dim regions (DESIGN.md §3.3).
    bool relativeTarget = false;
    std::uint64_t firstPass = 1u << 16;  // paths of the first learning pass; each pass doubles
    std::uint32_t maxCells = 1u << 15;
    // The first-bounce guide, learned on the same passes (DESIGN.md §3.4).
    GuideOptions guide;
    // The opening aim, learned on the same passes (DESIGN.md §3.5).
    OpeningAimOptions aim;
    // The share of path indices that start on the aim's panes and walk outwards (DESIGN.md §3.6,
    // kernels/lib/opening_walk.h); 0: none. Needs the aim.
    double openingsShare = 0.0;
    // The share chosen by the render itself from one pass raced in halves (--adaptive-openings-share
    // auto, the default; host/emission/openings_race.h); openingsShare is then unused.
    bool openingsAuto = true;
    // ... the least pass, in paths, that it races (--adaptive-openings-race-paths).
    std::uint64_t openingsRacePaths = std::uint64_t{1} << 22;
};

// The name --adaptive-estimate and the JSON give an estimate, and the estimate a name gives
// (nullptr for none): one table for both.
const char* estimateName(GridEstimate e);
const GridEstimate* estimateNamed(const std::string& name);

// The option ranges, checked before anything is built (fen::Error naming the option, the value
// and the range).
void validateAdaptiveOptions(const AdaptiveOptions& o);

// The command-line block (emission/strategy_registry.h).
std::unique_ptr<StrategyOptionBlock> makeAdaptiveOptionBlock();

// What a checkpoint must agree on (render/checkpoint.h).
nlohmann::json adaptiveFingerprint(const EmissionSettings& e);

}  // namespace fen
