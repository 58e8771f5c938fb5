// strategy.h — the seam between the render loop and the ways light paths start (DESIGN.md §3).
//
// An emission strategy owns the tables and device buffers of one way to draw emitted rays (x, v)
// and to weight them by their exact density: `uniform` (§3.1), `portal` (§3.2), `adaptive`
// (§3.3, over either as its base). The renderer knows only this interface:
//   - emitProgram(): the kernels/emit_<strategy>.cl that puts it in the one emission wrapper;
//   - bindEmitArgs(): its buffers, as emit_paths' arguments after (params, counters, paths);
//   - cellStats(): for a strategy that learns, the statistics connect.cl adds to;
//   - passLimit() / afterPaths(): a learning strategy runs in passes; after each the renderer hands
//     control back so that it can read its statistics and change its density;
//   - batchWeight(): what the batch just finished weighs in the image, in proportion to its
//     expected precision (paths over variance per path): a batch drawn while the density was
//     still being learned is noisier and weighs less (render/film.h BatchStatistics);
//   - guide(): a strategy that can learn the first bounce (the adaptive one, DESIGN.md §3.4)
//     returns its guide, whose buffers shade.cl and connect.cl are bound to (switched off, it
//     binds as placeholders); else nullptr;
//   - report(): what the JSON output says about it.
// Invariants: any sequence of passes gives unbiased images (every path's weight uses the density
// it was drawn from); the state after a pass depends only on the seed and the path counts, never
// on scheduling or pool size, so a render stays bit-identical for a seed.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cl/context.h"
#include "emission/adaptive_grid.h"
#include "scatter/first_bounce_guide.h"
#include "emission/portal_emission.h"
#include "scene/scene.h"
#include "sky/goniogram.h"
#include "sky/sky_tables.h"

namespace fen {

class StateReader;
class StateWriter;

enum class EmissionMethod { Uniform, Portal, Adaptive };
EmissionMethod parseEmissionMethod(const std::string& s);  // uniform | portal | adaptive
std::string methodName(EmissionMethod m);

// Settings of the adaptive strategy (DESIGN.md §3.3); defaults and the measurements behind them
// are in docs/results/adaptive.md.
struct AdaptiveOptions {
    EmissionMethod base = EmissionMethod::Uniform;  // Uniform or Portal
    int initialDepth = 3;      // origins: every region starts as 4^depth boxes ...
    int maxDepth = 10;         // ... split down to 2^-depth of the region's side
    int initialSkyDepth = 1;   // sky directions: 4^depth boxes of (1 - cos(theta), phi / 2 pi) ...
    int maxSkyDepth = 6;       // ... split down to 2^-depth of each side
    GridEstimate estimate = GridEstimate::Pooled;  // how <sum Lambda^2> is estimated per cell
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
};

struct EmissionSettings {
    EmissionMethod method = EmissionMethod::Uniform;
    std::string portals;  // --portals: node names replacing the scene's marking
    PortalOverlap overlap = PortalOverlap::Reject;
    // `portal`: the share of paths that estimate the light no portal passes (0: the paper's
    // method alone, no estimate).
    double portalComplement = 0.05;
    AdaptiveOptions adaptive;
};

// What a strategy is built from.
struct EmissionInputs {
    ocl::Context& ctx;
    const Scene& scene;
    const SkyTables& sky;                  // the scene's sky as tables ...
    const std::optional<Goniogram>& goniogram;
    const DeviceSky& deviceSky;            // ... and on the device
    int bvhWidth;                          // the scene's BVH layout, for portal sets
    double pixelFixedScale;                // RenderParams.fixed_scale (cell sums of Y use it too)
    int filmWidth = 0, filmHeight = 0;     // the image, for a strategy that steers by pixel
};

class EmissionStrategy {
public:
    virtual ~EmissionStrategy() = default;
    virtual EmissionMethod method() const = 0;
    virtual std::string emitProgram() const = 0;
    // Sets emit_paths' arguments from index `first` on (checked against the kernel's arity).
    virtual void bindEmitArgs(cl::Kernel& emit, cl_uint first) = 0;
    // Whether connect.cl gathers cell statistics for this strategy (-DFEN_EMISSION_STATS).
    virtual bool learns() const { return false; }
    // The statistics buffer connect.cl is bound to (a placeholder when the strategy does not learn).
    virtual const cl::Buffer& cellStats() const = 0;
    // Fixed-point units per (cd/m^2)^2 of the statistics (RenderParams.stats_scale).
    virtual double statsScale() const { return 0.0; }
    // A strategy that weighs its statistics by pixel (connect.cl's FEN_STATS_PIXEL_SCALE) returns
    // the per-pixel factors' buffer, and wants imageEstimate() after every pass; else nullptr.
    virtual const cl::Buffer* statsPixelScale() const { return nullptr; }
    // The image so far (luminance per pixel, row-major): deterministic for a seed and settings.
    virtual void imageEstimate(const std::vector<double>& luminance) { (void)luminance; }
    // The most paths the renderer may run before calling afterPaths again.
    virtual std::uint64_t passLimit() const { return std::numeric_limits<std::uint64_t>::max(); }
    // The wavefront has finished `paths` more paths; `batchEnd`: they end a batch.
    virtual void afterPaths(std::uint64_t paths, bool batchEnd) { (void)paths, (void)batchEnd; }
    // The weight of the batch that afterPaths(.., true) just ended, relative to the others; 1 for
    // a strategy whose density never changes (all batches alike).
    virtual double batchWeight() { return 1.0; }
    // The mean luminous flux a path carries when it starts (lm): what the light --max-bounces
    // removes is reported against it.
    virtual double emittedFluxPerPath() const = 0;
    // The first-bounce guide this strategy owns (perhaps off), or nullptr: the kernels then scatter
    // unguided.
    virtual FirstBounceGuide* guide() { return nullptr; }
    virtual nlohmann::json report() const = 0;
    // What the strategy has learned and recorded, between batches (when no statistics are on the
    // device), for a checkpoint; loadState() restores it exactly, so that a resumed render is
    // bit-identical (render/checkpoint.h).
    virtual void saveState(StateWriter& w) const { (void)w; }
    virtual void loadState(StateReader& r) { (void)r; }
};

std::unique_ptr<EmissionStrategy> makeEmissionStrategy(const EmissionSettings& settings,
                                                       const EmissionInputs& in);

}  // namespace fen
