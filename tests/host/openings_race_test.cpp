// openings_race_test.cpp — the openings' walks' share chosen by the render (host/emission/openings_race.h,
// DESIGN.md §3.6, --adaptive-openings-share auto), against its closed forms:
//   - choose(): at equal costs the predicted efficiency M0 / (a / S + b / (1 - S)) peaks at
//     S* = sqrt(a) / (sqrt(a) + sqrt(b)); with b = 0 (every light path's light is the walks') at the
//     largest share, with the gain 0.95 M0 / a; the rays per path interpolate between the two
//     measured shares; nothing measured chooses no walks;
//   - the phases: no race before the aim lists panes and a pass is large enough; a raced pass's
//     halves; a gain below the margin keeps share 0; the baseline is the lower of the half's and the
//     pass before's; a batch that ends in the first half races the next pass instead;
//   - a checkpoint carries the race (save, load, the same report), and a damaged one is refused.
#include <gtest/gtest.h>

#include <cmath>

#include "emission/openings_race.h"
#include "io/state_io.h"
#include "util/error.h"

namespace fen {
namespace {

constexpr std::uint64_t kMin = std::uint64_t{1} << 20;

TEST(OpeningsRace, ChoosesTheShareOfTheClosedForm)
{
    // equal costs: G(S) = M0 / (a / S + b / (1 - S)); a = 1, b = 1/9 peaks at S* = 1 / (1 + 1/3) = 0.75
    const RaceChoice c = OpeningsRace::choose(1.0, 3.0, 1.0, 1.0 / 9.0, 3.0, 0.5);
    EXPECT_NEAR(c.share, 0.75, 1e-12);
    EXPECT_NEAR(c.gain, 1.0 / (1.0 / 0.75 + (1.0 / 9.0) / 0.25), 1e-12);
    // b = 0: the largest share, gain 0.95 M0 / a
    const RaceChoice all = OpeningsRace::choose(2.0, 3.0, 1.0, 0.0, 3.0, 0.5);
    EXPECT_NEAR(all.share, OpeningsRace::kMaxShare, 1e-12);
    EXPECT_NEAR(all.gain, 0.95 * 2.0, 1e-12);
    // rays per path: c0 at 0, cB at the trial's share, linear between (and beyond): at S = 0.95 with
    // c0 = 2, cB = 4 at 0.5, c = 2 + 2 * 0.95 / 0.5 = 5.8
    const RaceChoice dear = OpeningsRace::choose(2.0, 2.0, 1.0, 0.0, 4.0, 0.5);
    EXPECT_NEAR(dear.share, 0.95, 1e-12);
    EXPECT_NEAR(dear.gain, 2.0 * 2.0 / ((1.0 / 0.95) * 5.8), 1e-12);
    // the shares start at the trial's: a = 1e-6, b = 1 would peak near 0 but is held at 0.5
    EXPECT_NEAR(OpeningsRace::choose(1.0, 1.0, 1e-6, 1.0, 1.0, 0.5).share, OpeningsRace::kMinShare, 1e-12);
    // nothing reached the camera: no walks
    EXPECT_EQ(OpeningsRace::choose(0.0, 1.0, 0.0, 0.0, 1.0, 0.5).gain, 0.0);
    EXPECT_EQ(OpeningsRace::choose(1.0, 1.0, 0.0, 0.0, 1.0, 0.5).gain, 0.0);
}

// One raced pass of 2n paths: the first half at share 0 (second moment m0, c0 rays a path), the
// second at the trial's share (the walks' and the light paths' parts, cB rays a path).
void racePass(OpeningsRace& r, double n, double m0, double c0, double walks, double light, double cB)
{
    ASSERT_TRUE(r.racing());
    EXPECT_EQ(r.share(), 0.0);
    const RacePass half{n, c0 * n, m0 * n, 0.0};
    r.afterHalf(half);
    EXPECT_EQ(r.share(), OpeningsRace::kTrialShare);
    r.afterPass({2 * n, half.rays + cB * n, half.lightSumSq + light * n, walks * n}, true, 2 * kMin);
}

TEST(OpeningsRace, WaitsForTheAimAndALargePassThenRacesTwoHalves)
{
    OpeningsRace r(true, 0.0, kMin);
    EXPECT_EQ(r.share(), 0.0);
    r.afterPass({1000, 3000, 1e9, 0}, false, 2 * kMin);  // no pane listed yet
    EXPECT_FALSE(r.racing());
    r.afterPass({1000, 3000, 1e9, 0}, true, kMin / 2);  // listed, but the next pass is small
    EXPECT_FALSE(r.racing());
    r.afterPass({1000, 3000, 4e3, 0}, true, kMin);  // the pass before the race: second moment 4
    EXPECT_TRUE(r.racing());
    // the walks carry everything (light part 0) at a walks' part 2 a path at share 0.5: a = 1,
    // b = 0; baseline min(5, 4) = 4; equal costs: gain 0.95 * 4 / 1 = 3.8 at share 0.95
    racePass(r, 1e6, 5.0, 3.0, 2.0, 0.0, 3.0);
    EXPECT_FALSE(r.racing());
    EXPECT_NEAR(r.share(), 0.95, 1e-12);
    const nlohmann::json j = r.report();
    EXPECT_EQ(j["phase"], "decided");
    EXPECT_NEAR(j["predicted_gain"].get<double>(), 3.8, 1e-9);
    EXPECT_NEAR(j["baseline"]["second_moment_per_path"].get<double>(), 5.0, 1e-12);
    EXPECT_NEAR(j["second_moment_used"].get<double>(), 4.0, 1e-12);
    // decided: later passes change nothing
    r.afterPass({1000, 1e9, 1e9, 1e9}, true, 2 * kMin);
    EXPECT_NEAR(r.share(), 0.95, 1e-12);
}

TEST(OpeningsRace, KeepsShareZeroBelowTheMargin)
{
    OpeningsRace r(true, 0.0, kMin);
    r.afterPass({1000, 3000, 0, 0}, true, kMin);  // nothing reached the camera before: no lower baseline
    // a = 0.5 * 1.2 = 0.6, b = 0; baseline 1; gain 0.95 / 0.6 = 1.58 at equal costs, but the trial
    // costs twice the rays: at 0.95, c = 3 + 3 * 0.95 / 0.5 = 8.7, gain 1.58 * 3 / 8.7 = 0.55
    racePass(r, 1e6, 1.0, 3.0, 1.2, 0.0, 6.0);
    EXPECT_EQ(r.share(), 0.0);
    const double g = r.report()["predicted_gain"].get<double>();
    EXPECT_LT(g, OpeningsRace::kMargin);
    EXPECT_GT(g, 0.0);
}

TEST(OpeningsRace, RacesTheNextPassWhenTheBatchEndsInTheFirstHalf)
{
    OpeningsRace r(true, 0.0, kMin);
    r.afterPass({1000, 3000, 4e3, 0}, true, kMin);
    ASSERT_TRUE(r.racing());
    r.afterPass({1000, 3000, 4e3, 0}, true, kMin);  // ended before its half: no decision
    EXPECT_TRUE(r.racing());
    EXPECT_EQ(r.share(), 0.0);
    racePass(r, 1e6, 5.0, 3.0, 2.0, 0.0, 3.0);
    EXPECT_NEAR(r.share(), 0.95, 1e-12);
}

TEST(OpeningsRace, AFixedShareNeverRaces)
{
    OpeningsRace r(false, 0.9, kMin);
    EXPECT_NEAR(r.share(), 0.9, 1e-12);
    r.afterPass({1e7, 3e7, 1e9, 0}, true, 2 * kMin);
    EXPECT_FALSE(r.racing());
    EXPECT_NEAR(r.share(), 0.9, 1e-12);
    EXPECT_EQ(r.report()["phase"], "fixed");
}

TEST(OpeningsRace, ACheckpointCarriesTheRace)
{
    OpeningsRace r(true, 0.0, kMin);
    r.afterPass({1000, 3000, 4e3, 0}, true, kMin);
    racePass(r, 1e6, 5.0, 3.0, 2.0, 0.0, 3.0);
    StateWriter w;
    r.save(w);
    OpeningsRace back(true, 0.0, kMin);
    StateReader rd(w.bytes(), "test");
    back.load(rd);
    rd.end();
    EXPECT_EQ(back.share(), r.share());
    EXPECT_EQ(back.report().dump(), r.report().dump());
    // a share out of range is refused, naming the key
    StateWriter bad;
    bad.u64("adaptive.race_phase", 3);
    bad.f64s("adaptive.race", {1.5, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
    StateReader rb(bad.bytes(), "test");
    try {
        back.load(rb);
        FAIL() << "a share of 1.5 was loaded";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("adaptive.race"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace fen
