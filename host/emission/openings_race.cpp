// openings_race.cpp — the openings' walks' share raced from the passes' second moments
// (DESIGN.md §3.6; the model and its invariants are in openings_race.h).
#include "emission/openings_race.h"

#include <algorithm>
#include <cmath>

#include "io/state_io.h"

namespace fen {

const char* OpeningsRace::phaseName(Phase p)
{
    switch (p) {
    case Phase::Fixed: return "fixed";
    case Phase::Waiting: return "waiting";
    case Phase::Trial: return "trial";
    case Phase::Decided: return "decided";
    }
    return "unknown";
}

double OpeningsRace::share() const
{
    return phase_ == Phase::Trial ? (halfDone_ ? kTrialShare : 0.0) : share_;
}

void OpeningsRace::afterHalf(const RacePass& half)
{
    if (phase_ != Phase::Trial || halfDone_)
        return;
    half_ = half;
    halfDone_ = true;
}

void OpeningsRace::afterPass(const RacePass& pass, bool aimListed, std::uint64_t nextPassPaths)
{
    const bool ready = aimListed && nextPassPaths >= minPassPaths_;
    if (phase_ != Phase::Waiting && phase_ != Phase::Trial)
        return;
    const double paths = pass.paths - half_.paths;
    if (!halfDone_ || !(half_.paths > 0.0) || !(paths > 0.0)) {
        // a whole pass at share 0: not raced (too small, or the batch ended inside its first half);
        // race the next pass, if it can be
        if (pass.paths > 0.0 && !halfDone_)
            lastM0_ = pass.lightSumSq / pass.paths;
        halfDone_ = false;
        phase_ = ready ? Phase::Trial : Phase::Waiting;
        return;
    }
    // The baseline's second moment: the first half's, or the pass before's if lower. A second moment
    // is overestimated now and then by a rare large contribution, never much underestimated once
    // the grid has learned, and a grid that learns only lowers it: the lower of the two is the
    // better guess, and it errs towards no walks, today's renderer.
    m0_ = half_.lightSumSq / half_.paths;
    if (lastM0_ > 0.0)
        m0_ = std::min(m0_, lastM0_);
    c0_ = half_.rays / half_.paths;
    a_ = kTrialShare * pass.walkSumSq / paths;  // the walks started in the second half alone
    b_ = (1.0 - kTrialShare) * (pass.lightSumSq - half_.lightSumSq) / paths;
    cB_ = (pass.rays - half_.rays) / paths;
    const RaceChoice c = choose(m0_, c0_, a_, b_, cB_, kTrialShare);
    gain_ = c.gain;
    share_ = c.gain >= kMargin ? c.share : 0.0;
    halfDone_ = false;
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
    w.f64s("adaptive.race", {share_, m0_, c0_, a_, b_, cB_, gain_, lastM0_});
}

void OpeningsRace::load(StateReader& r)
{
    const std::uint64_t p = r.u64("adaptive.race_phase", static_cast<std::uint64_t>(Phase::Decided));
    if (p == static_cast<std::uint64_t>(Phase::Fixed))
        r.fail("adaptive.race_phase", "a fixed share, in a render that races it");
    phase_ = static_cast<Phase>(p);
    const std::vector<double> v = r.f64s("adaptive.race", 8, true);
    for (double x : v)
        r.finite("adaptive.race", x);
    if (!(v[0] >= 0.0 && v[0] <= kMaxShare))
        r.fail("adaptive.race", "a share outside [0, 0.95]");
    share_ = v[0], m0_ = v[1], c0_ = v[2], a_ = v[3], b_ = v[4], cB_ = v[5], gain_ = v[6], lastM0_ = v[7];
    halfDone_ = false;
}

nlohmann::json OpeningsRace::report() const
{
    nlohmann::json j = {{"phase", phaseName(phase_)}, {"share", share()}};
    if (phase_ == Phase::Fixed)
        return j;
    j["trial_share"] = kTrialShare;
    j["margin"] = kMargin;
    j["shares"] = {kMinShare, kMaxShare};
    j["min_pass_paths"] = minPassPaths_;
    j["baseline"] = {{"second_moment_per_path", m0_}, {"rays_per_path", c0_}};
    j["trial"] = {{"walks_second_moment", a_}, {"light_paths_second_moment", b_}, {"rays_per_path", cB_}};
    j["predicted_gain"] = gain_;
    return j;
}

}  // namespace fen
