// strategy.h — the seam between the render loop and the ways light paths start (DESIGN.md §3).
//
// An emission strategy owns the tables and device buffers of one way to draw emitted rays (x, v)
// and to weight them by their exact density: `uniform` (§3.1), `portal` (§3.2), `adaptive`
// (§3.3, over either as its base). Each is described once -- name, options, defaults,
// fingerprint, factory -- in emission/strategy_registry.h. The renderer knows only this interface:
//   - kernels(): what the kernels are built with and bound to for it -- its emission program
//     (kernels/emit_<strategy>.cl, put in the one emission wrapper), whether connect.cl gathers
//     statistics for it and where, and the first-bounce guide shade.cl and connect.cl use;
//   - bindEmitArgs(): its buffers, as emit_paths' last arguments (lib/emit_kernel.h);
//   - passLimit() / afterPaths(): a learning strategy runs in passes; after each the renderer hands
//     control back so that it can read its statistics and change its density (and openingsShare());
//   - imageEstimate(): the image so far, for a strategy that steers by pixel;
//   - batchWeight(): what the batch just finished weighs in the image, in proportion to its
//     expected precision (paths over variance per path): a batch drawn while the density was
//     still being learned is noisier and weighs less (render/film.h BatchStatistics);
//   - report() and warnings(): what the JSON output says about it, and what the user should know;
//   - saveState() / loadState(): what it has learned, for a checkpoint.
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
#include "emission/adaptive_options.h"
#include "emission/emission_method.h"
#include "emission/portal_options.h"
#include "scatter/first_bounce_guide.h"
#include "scatter/opening_aim.h"
#include "scene/scene.h"
#include "sky/goniogram.h"
#include "sky/sky_tables.h"
#include "team/summed_buffer.h"

namespace fen {

class StateReader;
class StateWriter;

// What a render's emission is: the method, the scene's portal marking (read by the strategies
// that start paths through portals), and every strategy's settings block, at its defaults unless
// set (the command line: emission/emission_options.h).
struct EmissionSettings {
    EmissionMethod method = EmissionMethod::Uniform;
    std::string portals;  // --portals: node names replacing the scene's marking
    PortalOptions portal;
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

// What the stage kernels are built with and bound to for a strategy (render/path_loop.h).
struct EmissionKernels {
    std::string emitProgram;               // kernels/emit_<strategy>.cl
    // The statistics connect.cl adds to (-DFEN_EMISSION_STATS when `gatherStats`; else a
    // placeholder), in fixed-point units of statsScale per (cd/m^2)^2 (RenderParams.stats_scale).
    bool gatherStats = false;
    const cl::Buffer* cellStats = nullptr;
    double statsScale = 0.0;
    // Per-pixel factors of the statistics (connect.cl's FEN_STATS_PIXEL_SCALE), for a strategy that
    // weighs them by pixel and wants imageEstimate() after every pass; else nullptr.
    const cl::Buffer* statsPixelScale = nullptr;
    // The first-bounce guide it learns (perhaps off: placeholders), or nullptr: the kernels then
    // scatter unguided.
    const FirstBounceGuide* guide = nullptr;
    // The opening aim it learns (perhaps off: placeholders), or nullptr: nothing is aimed at.
    const OpeningAim* aim = nullptr;
    // Paths may start on the aim's panes too (--adaptive-openings-share > 0 or auto): the emission
    // programs are built with -DFEN_OPENING_WALKS=1 (lib/emit_kernel.h), and without the walk's code
    // otherwise. The share itself is openingsShare(), pass by pass.
    bool openingWalks = false;
};

class EmissionStrategy {
public:
    virtual ~EmissionStrategy() = default;
    virtual EmissionMethod method() const = 0;
    virtual EmissionKernels kernels() const = 0;
    // Sets emit_paths' arguments from index `first` on (checked against the kernel's arity).
    virtual void bindEmitArgs(cl::Kernel& emit, cl_uint first) = 0;
    // The mean luminous flux a path carries when it starts (lm): what the light --max-bounces
    // removes is reported against it.
    virtual double emittedFluxPerPath() const = 0;
    // The most paths the renderer may run before calling afterPaths again; `batchLeft`: the paths
    // left in the batch, after which afterPaths ends the pass in any case.
    virtual std::uint64_t passLimit(std::uint64_t batchLeft) const
    {
        (void)batchLeft;
        return std::numeric_limits<std::uint64_t>::max();
    }
    // The path loop has finished `paths` more paths, which traced `rays` rays (extension, shadow and
    // the openings' walks': a cost that depends on the seed alone, not on the machine); `batchEnd`:
    // they end a batch.
    virtual void afterPaths(std::uint64_t paths, std::uint64_t rays, bool batchEnd)
    {
        (void)paths, (void)rays, (void)batchEnd;
    }
    // The share of the next paths that start on the opening aim's panes (RenderParams.openings_share).
    virtual double openingsShare() const { return 0.0; }
    // Whether it would rather learn from more passes before the counted batches (a render by time
    // then calibrates on, within its tenth of the budget): the openings' share still to be raced.
    virtual bool learningPending() const { return false; }
    // The image so far (luminance per pixel, row-major), when kernels().statsPixelScale is set:
    // deterministic for a seed and settings.
    virtual void imageEstimate(const std::vector<double>& luminance) { (void)luminance; }
    // The weight of the batch that afterPaths(.., true) just ended, relative to the others, given
    // its paths over a full batch's (`pathsShare`, below 1 for a render by time's last batch,
    // render/last_batch.h): that share for a strategy whose density never changes.
    virtual double batchWeight(double pathsShare) { return pathsShare; }
    // The JSON output's "emission" object (README "Render output").
    virtual nlohmann::json report() const = 0;
    // Warnings for the user once the render is done (each one line, without "warning: ").
    virtual std::vector<std::string> warnings() const { return {}; }
    // What the strategy has learned and recorded, between batches (when no statistics are on the
    // device), for a checkpoint; loadState() restores it exactly, so that a resumed render is
    // bit-identical (render/checkpoint.h).
    virtual void saveState(StateWriter& w) const { (void)w; }
    virtual void loadState(StateReader& r) { (void)r; }
    // The device statistics it learns from, as a team sums them after every pass
    // (team/shared_sums.h); none when it learns nothing.
    virtual std::vector<SummedBuffer> summedBuffers() const { return {}; }
};

}  // namespace fen
