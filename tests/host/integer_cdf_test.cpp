// integer_cdf_test.cpp — the source table's integer alias table (util/integer_cdf.h): every
// entry must keep exactly the units its CDF gives it, since the path weights divide by them.
// Exact counting over the columns, not sampling: a unit lost is a 2^-32 bias no test could see.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "util/integer_cdf.h"

namespace fen {
namespace {

// Units per entry as the table assigns them: column j gives threshold units to j, the rest to
// its alias.
std::vector<std::uint64_t> unitsFromAlias(const IntegerCdf& t, std::size_t entries)
{
    const std::uint64_t C = std::uint64_t{1} << t.aliasShift;
    std::vector<std::uint64_t> units(entries, 0);
    for (std::size_t j = 0; j < t.alias.size() / 2; ++j) {
        const std::uint32_t thr = t.alias[2 * j], alias = t.alias[2 * j + 1];
        EXPECT_LE(thr, C) << "column " << j;
        if (thr > 0) {
            EXPECT_LT(j, entries) << "a padding column keeps units";
            if (j < entries)
                units[j] += thr;
        }
        if (thr < C) {
            EXPECT_LT(alias, entries) << "column " << j;
            if (alias < entries)
                units[alias] += C - thr;
        }
    }
    return units;
}

void expectExact(const std::vector<double>& w)
{
    const IntegerCdf t = makeIntegerCdf(w);
    ASSERT_EQ(t.cdf.size(), w.size() + 1);
    EXPECT_EQ(t.cdf.back(), std::uint64_t{1} << 32);
    const std::size_t columns = t.alias.size() / 2;
    EXPECT_EQ(columns, std::size_t{1} << (32 - t.aliasShift));
    EXPECT_GE(columns, w.size());
    EXPECT_LT(columns, 2 * w.size() + 2) << "more than twice the entries";
    const auto units = unitsFromAlias(t, w.size());
    for (std::size_t e = 0; e < w.size(); ++e) {
        EXPECT_EQ(units[e], t.cdf[e + 1] - t.cdf[e]) << "entry " << e << " of " << w.size();
        if (w[e] > 0.0)
            EXPECT_GT(units[e], 0u) << "entry " << e << " can never be drawn";
        else
            EXPECT_EQ(units[e], 0u) << "empty entry " << e;
    }
}

TEST(IntegerCdf, AliasTableKeepsEveryEntrysUnits)
{
    expectExact({1.0});
    expectExact({0.0, 3.0});
    expectExact({5, 0, 1, 1e-12, 0, 30, 2, 2, 0, 7, 1e-9, 3});
    // A sky-sized table: many small cells, a dominant sun, a power of two and one past it.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (std::size_t n : {std::size_t{4096}, std::size_t{4097}, std::size_t{42925}}) {
        std::vector<double> w(n);
        for (auto& x : w)
            x = u(rng) < 0.05 ? 0.0 : std::pow(u(rng), 8.0);
        w[0] = 1e3;
        expectExact(w);
    }
}

TEST(IntegerCdf, PickFollowsTheColumns)
{
    const IntegerCdf t = makeIntegerCdf({5, 0, 1, 2});  // 4 columns of 2^30
    for (std::uint32_t j = 0; j < 4; ++j) {
        const std::uint32_t base = j << 30, thr = t.alias[2 * j];
        if (thr > 0) {
            EXPECT_EQ(t.pick(base + thr - 1), j);
        }
        if (thr < (1u << 30)) {
            EXPECT_EQ(t.pick(base + thr), t.alias[2 * j + 1]);
        }
    }
    EXPECT_NE(t.pick(1u << 30), 1u) << "the empty entry was drawn";
}

}  // namespace
}  // namespace fen
