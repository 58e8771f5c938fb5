// last_batch.h — the last batch of a render by time, fitted to the time left (DESIGN.md §5).
//
// A render by time runs equal batches while the next one fits in the budget. The batches are
// sized from the calibration's rate, which the render's own learning then moves (a learned density
// draws paths of another length; the openings' race may turn walks on after it), so the last whole
// batch that fits often ends well short of the budget: up to a batch, a sixteenth of it, and
// measured at 1.1-1.3 s of a 20-s render where the race turned walks on. The time left then goes
// to one smaller batch: its paths are the full batch's scaled by the time left over a batch's
// time, after the camera pass's part of a batch (which runs whole in any batch) is taken out of
// both. The batch weighs in the image in proportion to its paths (EmissionStrategy::batchWeight),
// so the mean stays a precision-weighted mean of independent batches and the standard errors hold.
// Invariants: the result is 0 (no last batch) or in [kMinShare, 1) of a full batch's paths (for a
// batch of 2 paths or more); a render by paths never has one (it runs its B batches).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace fen {

struct LastBatch {
    // Below this share of a full batch the batch's own costs (reading the film, learning, the
    // statistics) weigh more than its paths bring: none.
    static constexpr double kMinShare = 0.25;
    // The rate moves between batches; aim a little short so that the budget holds.
    static constexpr double kMargin = 0.95;

    // The paths of the last batch, or 0: `perBatch` paths took `batchSeconds` a batch, of which
    // `cameraSeconds` were the camera pass's, and `secondsLeft` remain of the budget.
    static std::uint64_t paths(std::uint64_t perBatch, double batchSeconds, double cameraSeconds, double secondsLeft)
    {
        const double light = batchSeconds - std::clamp(cameraSeconds, 0.0, 0.9 * batchSeconds);
        if (!(light > 0.0) || !(secondsLeft > 0.0) || perBatch == 0)
            return 0;
        const double share = kMargin * (secondsLeft - (batchSeconds - light)) / light;
        if (!(share >= kMinShare))
            return 0;
        const double p = static_cast<double>(perBatch);
        const double n = std::max(std::floor(share * p), std::ceil(kMinShare * p));
        // called when a whole batch does not fit, so the share is below 1 but for the clock's jitter
        return std::min(static_cast<std::uint64_t>(n), perBatch - 1);
    }
};

}  // namespace fen
