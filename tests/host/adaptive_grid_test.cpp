// adaptive_grid_test.cpp — learning the adaptive strategy's cell probabilities
// (host/emission/adaptive_grid.h) from statistics with known answers: eq. 7 with the defensive
// share, the pooled estimate, the prior for cells not seen yet, cells that carried nothing never
// dying, splitting exactly where the light inside a cell is uneven, and determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "emission/adaptive_grid.h"
#include "util/error.h"

namespace fen {
namespace {

// n sky cells of equal base probability in the disk region, side by side at depth 2.
std::vector<GridCell> cells(std::size_t n)
{
    std::vector<GridCell> v(n);
    for (std::size_t i = 0; i < n; ++i) {
        v[i].depth = 2;
        v[i].ix = static_cast<std::uint32_t>(i % 4);
        v[i].iy = static_cast<std::uint32_t>(i / 4);
        v[i].skyDepth = 1;
        v[i].base = 1.0;
    }
    return v;
}

// The base density over directions, for splits along the direction box: here, by solid angle.
void evenSky(const GridCell&, double share[4])
{
    for (int q = 0; q < 4; ++q)
        share[q] = 0.25;
}

AdaptiveGrid grid(std::vector<GridCell> c, const GridLearning& l) { return AdaptiveGrid(std::move(c), l, evenSky); }

// Statistics of a cell whose every path contributes `value` `rate` times on average, spread
// evenly over its sixteen parts.
std::vector<GridCell::Stats> even(double paths, double rate, double value)
{
    GridCell::Stats s;
    s.paths = paths / 16;
    s.connections = paths * rate / 16;
    s.sum = s.connections * value;
    s.sumSq = s.connections * value * value;
    return std::vector<GridCell::Stats>(16, s);
}

void feed(AdaptiveGrid& g, const std::vector<std::vector<GridCell::Stats>>& perCell)
{
    std::vector<GridCell::Stats> q;
    for (const auto& c : perCell)
        q.insert(q.end(), c.begin(), c.end());
    g.addPass(q);
}

TEST(AdaptiveGrid, LearnsEquation7WithTheDefensiveShare)
{
    for (GridEstimate e : {GridEstimate::Squares, GridEstimate::Pooled}) {
        GridLearning l;
        l.estimate = e;
        l.defensive = 0.2;
        l.maxDepth = 2;  // no splitting here
        l.maxSkyDepth = 1;
        AdaptiveGrid g = grid(cells(4), l);
        // <sum Lambda^2> per path = rate value^2 (contributions of equal value): 1, 4, 0.25, 16
        // times 1e4, so P_learned is proportional to 1 : 2 : 0.5 : 4 (the prior's 32 pseudo-paths
        // are lost in 10^10).
        feed(g, {even(1e10, 0.1, 316.2277660168379), even(1e10, 0.1, 632.4555320336759),
                 even(1e10, 0.1, 158.11388300841898), even(1e10, 0.1, 1264.9110640673518)});
        g.update();
        const double learned[4] = {1.0 / 7.5, 2.0 / 7.5, 0.5 / 7.5, 4.0 / 7.5};
        for (std::size_t i = 0; i < 4; ++i)
            EXPECT_NEAR(g.cells()[i].prob, 0.8 * learned[i] + 0.2 * 0.25, 1e-6) << "cell " << i;
    }
}

TEST(AdaptiveGrid, PooledEstimateReadsTheSpreadFromFirstMoments)
{
    // Two cells with the same mean flux per path; one delivers it as many small contributions, the
    // other as few large ones: the second moment (and P) is larger for the latter, by
    // sqrt(value ratio) = sqrt(10) with values 1 and 10.
    GridLearning l;
    l.estimate = GridEstimate::Pooled;
    l.defensive = 1e-9;
    l.maxDepth = 2;
    l.maxSkyDepth = 1;
    AdaptiveGrid g = grid(cells(2), l);
    feed(g, {even(1e6, 0.5, 1.0), even(1e6, 0.05, 10.0)});
    g.update();
    EXPECT_NEAR(g.cells()[1].prob / g.cells()[0].prob, std::sqrt(10.0), 1e-3);
}

TEST(AdaptiveGrid, LargerEstimateRaisesOnlyCellsHeavierThanTheirPooledFigure)
{
    // Four cells with the same mean flux per path (1, over half a connection a path). Cells 0-2
    // deliver it evenly (Lambda^2 per connection = 1); cell 3 in a heavy tail, its squares 100
    // times its pooled figure. The pooled estimate cannot tell them apart. `larger` scales the
    // pooled figures by the spread g = sum base squares / sum base pooled = (3 * 0.5 + 50) / 2, so
    // cells 0-2 read g * 0.5 and cell 3 its squares, 50: P3 / P0 = sqrt(50 / (0.5 g)).
    auto heavy = [](double paths) {
        std::vector<GridCell::Stats> p = even(paths, 0.5, 1.0);
        for (GridCell::Stats& s : p)
            s.sumSq *= 100.0;
        return p;
    };
    for (GridEstimate e : {GridEstimate::Pooled, GridEstimate::Larger}) {
        GridLearning l;
        l.estimate = e;
        l.defensive = 1e-9;
        l.maxDepth = 2;
        l.maxSkyDepth = 1;
        AdaptiveGrid g = grid(cells(4), l);
        feed(g, {even(1e8, 0.5, 1.0), even(1e8, 0.5, 1.0), even(1e8, 0.5, 1.0), heavy(1e8)});
        g.update();
        const double spread = (3 * 0.5 + 50.0) / 2.0;
        const double expected = e == GridEstimate::Pooled ? 1.0 : std::sqrt(50.0 / (0.5 * spread));
        EXPECT_NEAR(g.cells()[3].prob / g.cells()[0].prob, expected, 1e-4) << static_cast<int>(e);
        EXPECT_NEAR(g.cells()[1].prob / g.cells()[0].prob, 1.0, 1e-9);
    }
    // Where every cell's contributions are even, squares and pooled figures agree, g = 1, and
    // `larger` learns what `pooled` learns (up to the prior's pseudo-paths, lost in 10^10 paths).
    std::vector<double> probs[2];
    for (GridEstimate e : {GridEstimate::Pooled, GridEstimate::Larger}) {
        GridLearning l;
        l.estimate = e;
        l.maxDepth = 2;
        l.maxSkyDepth = 1;
        AdaptiveGrid g = grid(cells(3), l);
        feed(g, {even(1e10, 0.2, 5.0), even(1e10, 0.05, 40.0), even(1e10, 0.01, 3.0)});
        g.update();
        for (const GridCell& c : g.cells())
            probs[e == GridEstimate::Larger].push_back(c.prob);
    }
    for (std::size_t i = 0; i < 3; ++i)
        EXPECT_NEAR(probs[1][i] / probs[0][i], 1.0, 1e-6) << "cell " << i;
}

TEST(AdaptiveGrid, UnseenCellsGetTheBaseShareAndDarkCellsNeverDie)
{
    GridLearning l;
    l.defensive = 0.1;
    l.maxDepth = 2;
    l.maxSkyDepth = 1;
    AdaptiveGrid g = grid(cells(3), l);
    // Cell 0 lit, cell 1 never sampled, cell 2 sampled a million times without a contribution.
    feed(g, {even(1e6, 0.2, 5.0), even(0.0, 0.0, 0.0), even(1e6, 0.0, 0.0)});
    g.update();
    const auto& c = g.cells();
    for (const auto& cell : c)
        EXPECT_GE(cell.prob, 0.1 * cell.base / 3.0 - 1e-15) << "the defensive share is a floor";
    // The unseen cell is judged by the prior, an average visited cell: far above the dark one.
    EXPECT_GT(c[1].prob, 5.0 * c[2].prob);
    EXPECT_GT(c[0].prob, c[1].prob);
    // The dark cell's learned share decays like 1 / sqrt(paths) but stays positive.
    EXPECT_GT(g.learned()[2], 0.0);
    EXPECT_LT(g.learned()[2], 1e-2);
}

TEST(AdaptiveGrid, NothingSeenKeepsTheBaseDensity)
{
    AdaptiveGrid g = grid(cells(4), GridLearning{});
    feed(g, {even(1e5, 0, 0), even(1e5, 0, 0), even(1e5, 0, 0), even(1e5, 0, 0)});
    g.update();
    for (const auto& c : g.cells())
        EXPECT_DOUBLE_EQ(c.prob, 0.25);
}

TEST(AdaptiveGrid, SplitsWhereTheLightInsideACellIsUneven)
{
    GridLearning l;
    l.splitGain = 1e-3;
    AdaptiveGrid g = grid(cells(3), l);
    // Cell 0: all its light in origin quarter 3 (parts 3, 7, 11, 15); cell 1: all in direction
    // quarter 2 (parts 8..11); cell 2: even. Cell 0 splits along its origin box, cell 1 along its
    // direction box, cell 2 not at all; each child starts with its parts' statistics.
    const GridCell::Stats dark{0.0, 0.0, 1e5, 0.0};
    std::vector<GridCell::Stats> origin = even(16e5, 0.3, 2.0), sky = even(16e5, 0.3, 2.0);
    for (int p = 0; p < 16; ++p) {
        if (p % 4 != 3)
            origin[p] = dark;
        if (p / 4 != 2)
            sky[p] = dark;
    }
    feed(g, {origin, sky, even(16e5, 0.3, 2.0)});
    EXPECT_EQ(g.update(), 2u);
    ASSERT_EQ(g.cells().size(), 9u);
    double base = 0.0;
    for (const auto& c : g.cells())
        base += c.base;
    EXPECT_NEAR(base, 1.0, 1e-12);
    const GridCell& lit = g.cells()[3];  // cell 0's children in quadrant order: 0, 1, 2, 3
    EXPECT_EQ(lit.depth, 3u);
    EXPECT_EQ(lit.ix, 1u);
    EXPECT_EQ(lit.iy, 1u);
    EXPECT_EQ(lit.skyDepth, 1u);
    EXPECT_NEAR(lit.total().paths, 4e5, 1e-6);
    EXPECT_NEAR(lit.total().connections, 4 * 0.3e5, 1e-6);
    EXPECT_GT(lit.prob, 10.0 * g.cells()[0].prob);
    const GridCell& litSky = g.cells()[4 + 2];  // cell 1's children: direction quarter 2
    EXPECT_EQ(litSky.depth, 2u);
    EXPECT_EQ(litSky.skyDepth, 2u);
    EXPECT_EQ(litSky.is, 0u);
    EXPECT_EQ(litSky.it, 1u);
    EXPECT_NEAR(litSky.total().connections, 4 * 0.3e5, 1e-6);
    EXPECT_GT(litSky.prob, 10.0 * g.cells()[4].prob);
    EXPECT_EQ(g.cells()[8].depth, 2u) << "the even cell is not split";
    EXPECT_EQ(g.cells()[8].skyDepth, 1u);
}

TEST(AdaptiveGrid, StatisticsOutOfRangeFallBackToTheBase)
{
    // An overflowed sum must leave a valid grid: finite probabilities, every cell alive.
    AdaptiveGrid g = grid(cells(3), GridLearning{});
    std::vector<GridCell::Stats> inf = even(1e5, 0.1, 1.0);
    inf[5].sum = std::numeric_limits<double>::infinity();
    feed(g, {inf, even(1e5, 0.1, 1.0), even(1e5, 0.1, 1.0)});
    g.update();
    for (const auto& c : g.cells()) {
        EXPECT_TRUE(std::isfinite(c.prob));
        EXPECT_GT(c.prob, 0.0);
    }
}

TEST(AdaptiveGrid, DeterministicAndChecked)
{
    auto run = [] {
        AdaptiveGrid g = grid(cells(4), GridLearning{});
        feed(g, {even(1e5, 0.1, 3.0), even(2e5, 0.2, 1.0), even(1e3, 0.0, 0.0), even(5e4, 0.5, 7.0)});
        g.update();
        return g.checksum();
    };
    EXPECT_EQ(run(), run());
    AdaptiveGrid g = grid(cells(2), GridLearning{});
    EXPECT_THROW(g.setProbabilities({1.0, 0.0}), Error) << "a cell with base light cannot get P = 0";
    EXPECT_THROW(g.setProbabilities({1.0}), Error);
    g.setProbabilities({1.0, 3.0});
    EXPECT_DOUBLE_EQ(g.cells()[1].prob, 0.75);
}

}  // namespace
}  // namespace fen
