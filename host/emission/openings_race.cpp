// openings_race.cpp — the openings' walks' share raced from the passes' second moments
// (DESIGN.md §3.6; the model and its invariants are in openings_race.h).
#include "emission/openings_race.h"

#include <algorithm>
#include <cmath>

#include "io/state_io.h"

namespace fen {

RacePass RacePass::minus(const RacePass& o) const
{
    return {paths - o.paths, rays - o.rays, lightSumSq - o.lightSumSq, walkSumSq - o.walkSumSq};
}

const char* OpeningsRace::phaseName(Phase p)
{
    switch (p) {
    case Phase::Fixed: return "fixed";
    case Phase::Waiting: return "waiting";
    case Phase::Ready: return "ready";  // the next pass large enough is raced
    case Phase::Decided: return "decided";
    }
    return "unknown";
}

double OpeningsRace::share() const
{
    return phase_ == Phase::Ready ? (halfDone_ ? kTrialShare : 0.0) : share_;
}

void OpeningsRace::afterHalf(const RacePass& half)
{
    if (phase_ != Phase::Ready || halfDone_)
        return;
    base_ = half;
    halfDone_ = true;
}

void OpeningsRace::afterPass(const RacePass& pass, bool aimListed, std::uint64_t nextPassPaths)
{
    if (phase_ != Phase::Waiting && phase_ != Phase::Ready)
        return;
    listed_ = aimListed;
    const bool ready = aimListed && nextPassPaths >= racePaths_;
    const RacePass second = pass.minus(base_);
    if (!halfDone_ || !(base_.paths > 0.0) || !(second.paths > 0.0)) {
        // a whole pass at share 0: not raced (too small, or the batch ended inside its first half);
        // race the next pass, if it can be
        if (pass.paths > 0.0 && !halfDone_)
            lastM0_ = pass.lightSumSq / pass.paths;
        halfDone_ = false;
        base_ = {};
        phase_ = ready ? Phase::Ready : Phase::Waiting;
        return;
    }
    halfDone_ = false;
    trial_ = second;
    decide();
}

void OpeningsRace::decide()
{
    // The baseline's second moment: the first half's, or the pass before the race's if lower. A
    // second moment is overestimated now and then by a rare large contribution, never much
    // underestimated once the grid has learned, and a grid that learns only lowers it: the lower of
    // the two is the better guess, and it errs towards no walks, today's renderer.
    m0_ = base_.lightSumSq / base_.paths;
    if (lastM0_ > 0.0)
        m0_ = std::min(m0_, lastM0_);
    const double a = kTrialShare * trial_.walkSumSq / trial_.paths;
    const double b = (1.0 - kTrialShare) * trial_.lightSumSq / trial_.paths;
    const RaceChoice c = choose(m0_, base_.rays / base_.paths, a, b, trial_.rays / trial_.paths, kTrialShare);
    gain_ = c.gain;
    share_ = c.gain >= kMargin ? c.share : 0.0;
    phase_ = Phase::Decided;
}

RaceChoice OpeningsRace::choose(double m0, double c0, double a, double b, double cB, double trialShare)
{
    RaceChoice best;
    if (!(m0 > 0.0 && c0 > 0.0 && cB > 0.0 && a >= 0.0 && b >= 0.0 && a + b > 0.0 && trialShare > 0.0))
        return best;  // nothing measured (no light reached the camera): no walks
    const double floorCost = 0.1 * std::min(c0, cB);
    for (int k = 0; kMinShare + k * kShareStep <= kMaxShare + 1e-9; ++k) {
        const double S = kMinShare + k * kShareStep;
        const double m = a / S + b / (1.0 - S);
        const double c = std::max(floorCost, c0 + (cB - c0) * S / trialShare);
        const double g = m0 * c0 / (m * c);
        if (g > best.gain)
            best = {S, g};
    }
    return best;
}

void OpeningsRace::save(StateWriter& w) const
{
    w.u64("adaptive.race_phase", static_cast<std::uint64_t>(phase_));
    w.f64s("adaptive.race", {share_, lastM0_, m0_, gain_, base_.paths, base_.rays, base_.lightSumSq, base_.walkSumSq,
                             trial_.paths, trial_.rays, trial_.lightSumSq, trial_.walkSumSq});
}

void OpeningsRace::load(StateReader& r)
{
    const std::uint64_t p = r.u64("adaptive.race_phase", static_cast<std::uint64_t>(Phase::Decided));
    if (p == static_cast<std::uint64_t>(Phase::Fixed))
        r.fail("adaptive.race_phase", "a fixed share, in a render that races it");
    phase_ = static_cast<Phase>(p);
    const std::vector<double> v = r.f64s("adaptive.race", 12, true);
    for (double x : v)
        if (!(r.finite("adaptive.race", x) >= 0.0))
            r.fail("adaptive.race", "a negative value");
    if (v[0] > kMaxShare)
        r.fail("adaptive.race", "a share outside [0, 0.95]");
    share_ = v[0], lastM0_ = v[1], m0_ = v[2], gain_ = v[3];
    base_ = {v[4], v[5], v[6], v[7]};
    trial_ = {v[8], v[9], v[10], v[11]};
    halfDone_ = false;
}

nlohmann::json OpeningsRace::report() const
{
    nlohmann::json j = {{"phase", phaseName(phase_)}, {"share", share()}};
    if (phase_ == Phase::Fixed)
        return j;
    const auto perPath = [](double v, double n) { return n > 0.0 ? v / n : 0.0; };
    j["race_paths"] = racePaths_;
    j["trial_share"] = kTrialShare;
    j["margin"] = kMargin;
    j["shares"] = {kMinShare, kMaxShare};
    j["baseline"] = {{"paths", base_.paths},
                     {"second_moment_per_path", perPath(base_.lightSumSq, base_.paths)},
                     {"pass_before_second_moment_per_path", lastM0_},
                     {"rays_per_path", perPath(base_.rays, base_.paths)}};
    j["trial"] = {{"paths", trial_.paths},
                  {"walks_second_moment", kTrialShare * perPath(trial_.walkSumSq, trial_.paths)},
                  {"light_paths_second_moment", (1.0 - kTrialShare) * perPath(trial_.lightSumSq, trial_.paths)},
                  {"rays_per_path", perPath(trial_.rays, trial_.paths)}};
    j["second_moment_used"] = m0_;
    j["predicted_gain"] = gain_;
    return j;
}

}  // namespace fen
