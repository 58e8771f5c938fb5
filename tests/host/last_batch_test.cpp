// last_batch_test.cpp — a render by time's last batch, fitted to the time left
// (host/render/last_batch.h), against its closed forms; and the film's statistics with that batch
// weighed by its share of a full batch's paths (render/film.h BatchStatistics), against the
// variance of a precision-weighted mean.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "render/film.h"
#include "render/last_batch.h"

namespace fen {
namespace {

TEST(LastBatch, ThePathsFitTheTimeLeft)
{
    // 1000 paths took 2 s a batch, 0.4 s of it the camera pass's (which a last batch runs whole):
    // 1 s left leaves 0.6 s for paths, 0.6 / 1.6 of a batch, times the margin 0.95.
    EXPECT_EQ(LastBatch::paths(1000, 2.0, 0.4, 1.0), static_cast<std::uint64_t>(std::floor(0.95 * 0.6 / 1.6 * 1000)));
    // without a camera pass: 0.95 * 1 / 2 of a batch
    EXPECT_EQ(LastBatch::paths(1000, 2.0, 0.0, 1.0), 475u);
    // a whole batch (clock jitter past the check) is still short of one
    EXPECT_EQ(LastBatch::paths(1000, 2.0, 0.0, 2.5), 999u);
}

TEST(LastBatch, NoneWhenTooLittleIsLeft)
{
    EXPECT_EQ(LastBatch::paths(1000, 2.0, 0.0, 0.5), 0u);   // 0.2375 of a batch: under a quarter
    EXPECT_GT(LastBatch::paths(1000, 2.0, 0.0, 0.54), 0u);  // 0.2565: over
    EXPECT_EQ(LastBatch::paths(1000, 2.0, 0.4, 0.4), 0u);   // the camera pass alone would fill it
    EXPECT_EQ(LastBatch::paths(1000, 2.0, 0.0, -1.0), 0u);  // already past the budget
    EXPECT_EQ(LastBatch::paths(0, 2.0, 0.0, 1.0), 0u);
    EXPECT_EQ(LastBatch::paths(1000, 0.0, 0.0, 1.0), 0u);
    EXPECT_EQ(LastBatch::paths(1, 2.0, 0.0, 1.5), 0u);      // a batch of one path has no smaller one
    // just over a quarter of 1001 paths rounds down to 250, under the quarter: 251, the least that is not
    EXPECT_EQ(LastBatch::paths(1001, 2.0, 0.0, 0.5264), 251u);
}

// Fifteen batches of N paths and a last one of N/4, each batch's value the mean of its paths'
// (drawn as a normal of variance 1/n), the last weighed by its share 1/4: over many renders the
// mean is unbiased, its variance is 1 / (15.25 N), the precision-weighted optimum (equal weights
// would give (15 + 4) / 256 / N, 1.13 times more), and the film's standard error estimates it.
TEST(LastBatch, WeighedByItsPathsTheMeanAndItsErrorHold)
{
    const int renders = 20000, whole = 15;
    const double n = 1000.0, mu = 3.0;
    std::mt19937_64 rng(20261205);
    std::normal_distribution<double> unit(0.0, 1.0);
    double sum = 0.0, sumSq = 0.0, sumSe2 = 0.0;
    for (int k = 0; k < renders; ++k) {
        BatchStatistics st(1, 1, {Roi{0, 0, 1, 1}});
        for (int b = 0; b <= whole; ++b) {
            const double share = b < whole ? 1.0 : 0.25;
            const double v = mu + unit(rng) / std::sqrt(share * n);
            st.add({v, v, v}, share);
        }
        const double m = st.mean().rgb[0];
        const double se = st.stdErrLuminance()[0];
        sum += m;
        sumSq += m * m;
        sumSe2 += se * se;
    }
    const double mean = sum / renders;
    const double variance = (sumSq - renders * mean * mean) / (renders - 1);
    const double expected = 1.0 / (15.25 * n);
    // 4 sigma: the mean's own standard error; a variance's relative standard error sqrt(2 / (R - 1))
    EXPECT_NEAR(mean, mu, 4.0 * std::sqrt(expected / renders));
    const double rel = 4.0 * std::sqrt(2.0 / (renders - 1));
    EXPECT_NEAR(variance / expected, 1.0, rel);
    // the mean of the squared standard errors (each from 15 degrees of freedom: its own relative
    // spread sqrt(2 / 15) per render, over R renders)
    EXPECT_NEAR(sumSe2 / renders / expected, 1.0, 4.0 * std::sqrt(2.0 / 15.0 / renders));
}

}  // namespace
}  // namespace fen
