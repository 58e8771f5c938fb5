// in_shares_test.cpp — util/in_shares.h: every item in exactly one chunk, whatever n and the
// smallest chunk; an exception in any chunk reaches the caller after the threads have joined, and
// the other chunks still run.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

#include "util/in_shares.h"

namespace fen {
namespace {

TEST(InShares, EveryItemOnceInChunksOfAtLeastTheSmallest)
{
    for (std::size_t n : {0u, 1u, 2u, 17u, 1000u, 4097u})
        for (std::size_t minPerShare : {1u, 64u}) {
            std::vector<std::atomic<int>> seen(n);
            std::atomic<std::size_t> calls{0};
            inShares(n, [&](std::size_t a, std::size_t b) {
                ++calls;
                EXPECT_LE(a, b);
                EXPECT_TRUE(b - a >= minPerShare || b == n) << "a chunk smaller than asked, not the last";
                for (std::size_t i = a; i < b; ++i)
                    ++seen[i];
            }, minPerShare);
            for (std::size_t i = 0; i < n; ++i)
                EXPECT_EQ(seen[i].load(), 1) << "n " << n << ", item " << i;
            EXPECT_GE(calls.load(), 1u);
            EXPECT_LE(calls.load(), std::max<std::size_t>(1, (n + minPerShare - 1) / minPerShare)) << "n " << n;
        }
}

TEST(InShares, AnExceptionInAChunkReachesTheCaller)
{
    // The item that throws lies in the last chunk whatever the machine's thread count.
    const std::size_t n = 1000;
    std::atomic<std::size_t> done{0};
    EXPECT_THROW(inShares(n, [&](std::size_t a, std::size_t b) {
        for (std::size_t i = a; i < b; ++i) {
            if (i == n - 1)
                throw std::runtime_error("item 999");
            ++done;
        }
    }), std::runtime_error);
    EXPECT_EQ(done.load(), n - 1) << "the other chunks ran to their end";
}

}  // namespace
}  // namespace fen
