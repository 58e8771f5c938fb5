// in_shares_test.cpp — util/in_shares.h: every item in exactly one share, whatever n and the
// smallest share; an exception in any share reaches the caller after the threads have joined.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

#include "util/in_shares.h"

namespace fen {
namespace {

TEST(InShares, EveryItemOnceInContiguousShares)
{
    for (std::size_t n : {0u, 1u, 2u, 17u, 1000u, 4097u})
        for (std::size_t minPerShare : {1u, 64u}) {
            std::vector<std::atomic<int>> seen(n);
            std::atomic<std::size_t> shares{0};
            inShares(n, [&](std::size_t a, std::size_t b) {
                ++shares;
                EXPECT_LE(a, b);
                for (std::size_t i = a; i < b; ++i)
                    ++seen[i];
            }, minPerShare);
            for (std::size_t i = 0; i < n; ++i)
                EXPECT_EQ(seen[i].load(), 1) << "n " << n << ", item " << i;
            EXPECT_GE(shares.load(), 1u);
            EXPECT_LE(shares.load(), std::max<std::size_t>(1, n / minPerShare)) << "n " << n;
        }
}

TEST(InShares, AnExceptionInAShareReachesTheCaller)
{
    // The item that throws lies in the last share whatever the machine's thread count.
    const std::size_t n = 1000;
    std::atomic<std::size_t> done{0};
    EXPECT_THROW(inShares(n, [&](std::size_t a, std::size_t b) {
        for (std::size_t i = a; i < b; ++i) {
            if (i == n - 1)
                throw std::runtime_error("item 999");
            ++done;
        }
    }), std::runtime_error);
    EXPECT_EQ(done.load(), n - 1) << "the other shares ran to their end";
}

}  // namespace
}  // namespace fen
