// openings_race.h — the openings' walks' share, chosen by the render from its own passes
// (DESIGN.md §3.6, --adaptive-openings-share auto).
//
// The walks pay where the light that comes in has bounced outside first (a room lit by a sunlit
// facing wall), and cost where it comes in straight or crosses rooms after it enters. Which a scene
// is shows in the passes' own statistics: the sum over every contribution that reached the camera of
// its squared luminance, per path, is the image's second moment, nearly its variance for a light
// tracer; times the rays per path (a cost that depends on the seed alone) it is the inverse of the
// efficiency. So, once the opening aim lists panes, the first pass of at least N paths
// (--adaptive-openings-race-paths, 2^22 by default) is raced in two halves with the same emission
// grid, guide and aim (nothing is learned between them, so neither half is the better learned):
//   - the first half, at share 0, gives M0 (second moment per path) and c0 (rays per path);
//   - the second half, at share s, gives the walks' part W and the light paths' part L of its
//     second moment per path, and cB. At share S a path is a walk with probability S, weighing 1 / S,
//     or a light path, weighing 1 / (1 - S), so the second moment is
//         M(S) = a / S + b / (1 - S),   a = s W, b = (1 - s) L,
//     and the rays per path, between the two measured shares, c(S) = c0 + (cB - c0) S / s;
//   - the predicted efficiency over share 0 is G(S) = M0 c0 / (M(S) c(S)); the share is the S in
//     [kMinShare, kMaxShare] (steps of kShareStep) with the largest G, if that G is at least kMargin,
//     else 0 (no walks). M0 is the first half's or the whole pass before the race's, whichever is
//     lower (a rare large contribution inflates a second moment far more often than the lack of one
//     deflates it). The shares start at the trial's: below it, the light paths' side of the trial
//     (no aim mixture, ended at a listed pane) would decide more than the walks.
// Why a pass this large: the second moment of a smaller one is too uncertain (its largest
// contributions are rare), and the grid has learned too little for the light paths to be judged
// fairly (their second moment falls a hundredfold while it learns; the walks' does not: raced at
// passes of 2^21 the houses chose walks that cost them). Measured on the shipped scenes in
// docs/results/guiding.md, "The openings' share raced". In a render by time the renderer's
// calibration goes on until that pass has run, while it is under a tenth of the budget (pending()),
// so that the race costs the counted batches nothing.
// The decision is a function of fixed-point sums and ray counts, so the same seed chooses the same
// share at any pool size, in either kernel form, and in a team (whose sums are the team's).
// Invariants: share() is in [0, 1); before the decision it is 0 or the trial's share; a checkpoint
// (between batches, so never inside a raced pass) carries the phase and the sums.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

namespace fen {

class StateReader;
class StateWriter;

// Measurements of paths run: their count, their rays, and the squared luminances (cd^2/m^4, summed
// over the contributions that reached the camera) of the light paths' and the walks' contributions.
struct RacePass {
    double paths = 0.0, rays = 0.0, lightSumSq = 0.0, walkSumSq = 0.0;
    RacePass minus(const RacePass& o) const;
};

// The share with the largest predicted efficiency over share 0, and that efficiency.
struct RaceChoice {
    double share = 0.0, gain = 0.0;
};

class OpeningsRace {
public:
    // The trial halves' share, the shares a decision chooses among, and the least predicted gain
    // that turns the walks on.
    static constexpr double kTrialShare = 0.5;
    static constexpr double kMargin = 1.25;
    static constexpr double kMinShare = 0.5, kShareStep = 0.05, kMaxShare = 0.95;

    // `autoShare`: race a pass of `racePaths` paths or more; else the walks' share is `fixedShare`
    // throughout (0: none).
    OpeningsRace(bool autoShare, double fixedShare, std::uint64_t racePaths)
        : share_(autoShare ? 0.0 : fixedShare), phase_(autoShare ? Phase::Waiting : Phase::Fixed),
          racePaths_(racePaths)
    {
    }

    // The share of the paths of the next piece of a pass that start on the panes.
    double share() const;
    // Whether the pass under way is raced (its first half at share 0, the rest at the trial's
    // share: the strategy ends a piece there), and whether that half is done.
    bool racing() const { return phase_ == Phase::Ready; }
    bool halfDone() const { return halfDone_; }
    // Whether the race is still to run and the aim lists panes: passes before the counted batches
    // are worth running for it.
    bool pending() const { return phase_ == Phase::Ready || (phase_ == Phase::Waiting && listed_); }
    // The first half of a pass that will run `passPaths` paths, or 0 when it is too small to race
    // (then it runs at share 0, and the next pass is raced if it can be).
    std::uint64_t half(std::uint64_t passPaths) const { return passPaths >= racePaths_ ? passPaths / 2 : 0; }
    // The raced pass's first half ended: the pass's measurements so far.
    void afterHalf(const RacePass& half);
    // A pass ended: its measurements (the whole pass's); whether the aim lists panes for the next
    // pass, and how many paths the next pass will have at most.
    void afterPass(const RacePass& pass, bool aimListed, std::uint64_t nextPassPaths);

    // The decision from the measurements (see the file's head).
    static RaceChoice choose(double m0, double c0, double a, double b, double cB, double trialShare);

    void save(StateWriter& w) const;
    void load(StateReader& r);
    nlohmann::json report() const;

private:
    enum class Phase { Fixed, Waiting, Ready, Decided };
    static const char* phaseName(Phase p);
    void decide();
    double share_;
    Phase phase_;
    std::uint64_t racePaths_;
    bool halfDone_ = false;
    bool listed_ = false;           // the aim listed panes after the last pass
    RacePass base_, trial_;         // the raced pass's halves: at share 0, at the trial's share
    double lastM0_ = 0.0;           // the last whole pass at share 0 before it: second moment per path
    double m0_ = 0.0, gain_ = 0.0;  // the baseline's second moment used, the chosen share's gain
};

}  // namespace fen
