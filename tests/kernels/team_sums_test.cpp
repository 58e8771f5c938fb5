// team_sums_test.cpp — the team's device sums (host/team/shared_sums.h, kernels/team_sums.cl)
// against the host's 128-bit arithmetic (util/fixed_point.h add128, sub128): a buffer of mixed records
// (two 128-bit sums and a count) holding arbitrary words, changed by "this member's pass", then
// summed with another member's differences, must hold before + both, with every carry, borrow and
// wrap exact; and the same from zeros, where nothing is copied.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "support/cl_fixture.h"
#include "team/shared_sums.h"

namespace fen {
namespace {

// A team of two whose other member's differences are known: sum() adds them.
class TwoWithAKnownOther final : public Team {
public:
    explicit TwoWithAKnownOther(std::vector<U128> other) : other_(std::move(other)) {}
    int rank() const override { return 0; }
    int size() const override { return 2; }
    int localRank() const override { return 0; }
    void sum(std::vector<U128>& v) override
    {
        ASSERT_EQ(v.size(), other_.size());
        for (std::size_t i = 0; i < v.size(); ++i)
            v[i] = add128(v[i], other_[i]);
    }
    void broadcast(std::string&) override {}
    std::vector<double> gather(double v) override { return {v, v}; }
    std::vector<std::string> gatherToRoot(const std::string& t) override { return {t, t}; }
    std::uint64_t ticket() override { return 0; }
    std::string describe() const override { return "a test's two"; }

private:
    std::vector<U128> other_;
};

// Random words, a quarter of them near 2^64 so that additions carry and differences borrow.
std::uint64_t word(std::mt19937_64& rng)
{
    const std::uint64_t w = rng();
    return (w & 3u) == 0 ? ~std::uint64_t{0} - (w >> 60) : w;
}

void checkPass(bool zero)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    constexpr std::size_t kRecords = 1000;
    const std::vector<int> fields{2, 2, 1};  // as an emission cell's statistics
    std::mt19937_64 rng(zero ? 11 : 7);
    std::vector<std::uint64_t> start(kRecords * 5, 0);
    if (!zero)
        for (auto& w : start)
            w = word(rng);
    cl::Buffer buf = ctx->buffer(CL_MEM_READ_WRITE, start.size() * 8, "summed", start.data());
    // this member's pass adds `own`; the other member's differences are `other` (+ 2 extras)
    std::vector<U128> own, other;
    std::vector<std::uint64_t> after = start, expect = start;
    for (std::size_t r = 0; r < kRecords; ++r)
        for (std::size_t f = 0, w = r * 5; f < fields.size(); w += static_cast<std::size_t>(fields[f]), ++f) {
            const U128 a{word(rng), fields[f] == 2 ? word(rng) : 0}, b{word(rng), fields[f] == 2 ? word(rng) : 0};
            own.push_back(a);
            other.push_back(b);
            if (fields[f] == 2) {
                const U128 mine = add128({after[w], after[w + 1]}, a);
                after[w] = mine.lo, after[w + 1] = mine.hi;
                const U128 both = add128(add128({expect[w], expect[w + 1]}, a), b);
                expect[w] = both.lo, expect[w + 1] = both.hi;
            } else {
                after[w] += a.lo;
                expect[w] += a.lo + b.lo;
            }
        }
    other.push_back({5, 0});
    other.push_back({0, 0});
    TwoWithAKnownOther team(other);
    SharedSums sums(*ctx, team);
    sums.before({{&buf, kRecords, fields}}, zero);
    ctx->queue().enqueueWriteBuffer(buf, CL_TRUE, 0, after.size() * 8, after.data());  // the "pass"
    std::vector<U128> extra{{3, 0}, {1, 0}};
    sums.after(extra);
    std::vector<std::uint64_t> got(expect.size());
    ctx->queue().enqueueReadBuffer(buf, CL_TRUE, 0, got.size() * 8, got.data());
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < got.size(); ++i)
        wrong += got[i] != expect[i] ? 1 : 0;
    EXPECT_EQ(wrong, 0u) << "of " << got.size() << " words";
    EXPECT_EQ(extra[0].lo, 8u);
    EXPECT_EQ(extra[1].lo, 1u);
    const auto report = sums.report();
    EXPECT_EQ(report["reductions"], 1);
    EXPECT_EQ(report["bytes"], (kRecords * fields.size() + 2) * 16);
}

TEST(TeamSums, ThePassAndTheOtherMembersAddExactly) { checkPass(false); }

TEST(TeamSums, FromZerosNothingIsCopied) { checkPass(true); }

}  // namespace
}  // namespace fen
