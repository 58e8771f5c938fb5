// team_test.cpp — the team's collectives (host/team/; DESIGN.md §9) without a device: the 128-bit
// sum carries from the low word into the high and wraps as the device's accumulators do; members
// of a ThreadTeam get the same sums, the root's bytes and everyone's numbers; a member that fails
// releases the others with an error instead of leaving them waiting.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "team/team.h"
#include "team/thread_team.h"
#include "util/error.h"

namespace fen {
namespace {

TEST(Team, Add128CarriesAndSub128Borrows)
{
    const U128 a{~0ull, 1}, b{1, 2};
    const U128 s = add128(a, b);
    EXPECT_EQ(s.lo, 0u);
    EXPECT_EQ(s.hi, 4u);
    const U128 d = sub128(s, b);
    EXPECT_EQ(d.lo, a.lo);
    EXPECT_EQ(d.hi, a.hi);
    // wraps modulo 2^128, so a difference that went "negative" adds back exactly
    const U128 w = add128(sub128(b, a), a);
    EXPECT_EQ(w.lo, b.lo);
    EXPECT_EQ(w.hi, b.hi);
}

TEST(Team, TheSoloTeamChangesNothing)
{
    Team& t = soloTeam();
    std::vector<U128> v{{5, 6}};
    t.sum(v);
    EXPECT_EQ(v[0].lo, 5u);
    EXPECT_EQ(sumOver(t, 7), 7u);
    EXPECT_TRUE(anyMember(t, true));
    EXPECT_EQ(fromRoot(t, 2.5), 2.5);
    EXPECT_EQ(t.gather(3.0), std::vector<double>{3.0});
}

TEST(Team, ThreadMembersShareSumsBytesAndNumbers)
{
    constexpr int kMembers = 3, kRounds = 200;
    ThreadTeam team(kMembers);
    std::vector<int> bad(kMembers, 0);
    const auto member = [&](int k) {
        Team& t = team.member(k);
        for (int round = 0; round < kRounds; ++round) {
            // each member's low word near 2^64: the sum must carry into the high word
            std::vector<U128> v{{~0ull - static_cast<std::uint64_t>(k), static_cast<std::uint64_t>(round)},
                                {static_cast<std::uint64_t>(k + 1), 0}};
            t.sum(v);
            // sum of (2^64 - 1 - k) over k = 0..2 is 3 * 2^64 - 6: low 2^64 - 6, carry 2
            if (v[0].lo != ~0ull - 5 || v[0].hi != 3u * static_cast<std::uint64_t>(round) + 2 || v[1].lo != 6u)
                ++bad[static_cast<std::size_t>(k)];
            std::string bytes = k == 0 ? "round " + std::to_string(round) : "mine";
            t.broadcast(bytes);
            if (bytes != "round " + std::to_string(round))
                ++bad[static_cast<std::size_t>(k)];
            if (t.gather(k * 10.0 + round) != std::vector<double>{0.0 + round, 10.0 + round, 20.0 + round})
                ++bad[static_cast<std::size_t>(k)];
        }
    };
    std::vector<std::thread> threads;
    for (int k = 0; k < kMembers; ++k)
        threads.emplace_back(member, k);
    for (auto& th : threads)
        th.join();
    EXPECT_EQ(bad, std::vector<int>(kMembers, 0));
}

TEST(Team, AFailedThreadMemberReleasesTheOthers)
{
    ThreadTeam team(2);
    bool released = false;
    std::thread waiting([&] {
        std::vector<U128> v{{1, 0}};
        try {
            team.member(1).sum(v);  // member 0 never comes
        } catch (const Error& e) {
            released = std::string(e.what()).find("another device") != std::string::npos;
        }
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    team.breakTeam();
    waiting.join();
    EXPECT_TRUE(released);
    // and a member that arrives after the failure does not wait either
    std::vector<U128> v{{1, 0}};
    EXPECT_THROW(team.member(0).sum(v), Error);
}

}  // namespace
}  // namespace fen
