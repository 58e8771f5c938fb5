// thread_team.h — several OpenCL devices in one process as a team (team/team.h): one member per
// device, each a thread running the whole render loop on its own context (DESIGN.md §9).
//
// The collectives meet at a barrier: every member adds its part to the step's result as it
// arrives, and all leave with the result once the last has arrived. A member that fails (its device, its memory) marks the
// team broken before it leaves; every member waiting, or arriving later, then stops with an error
// instead of waiting for it, so a failed device ends the render in bounded time, and the render
// reports the first member's own error.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "team/team.h"

namespace fen {

class ThreadTeam {
public:
    explicit ThreadTeam(int members);
    ~ThreadTeam();
    // Member k's view of the team, for the thread that runs it.
    Team& member(int k);
    int size() const { return size_; }
    // A member failed: everyone waiting, or still to come, gives up (Error).
    void breakTeam();

private:
    class Member;
    friend class Member;
    // The collective step every member takes: `deposit` its part under the lock on arrival (the
    // parts combine as they arrive), `collect` the result under the lock once all have arrived.
    template <typename Deposit, typename Collect>
    void meet(Deposit deposit, Collect collect);

    int size_;
    std::vector<std::unique_ptr<Member>> members_;
    std::mutex mutex_;
    std::condition_variable cv_;
    int arrived_ = 0, left_ = 0;
    std::uint64_t generation_ = 0;
    bool broken_ = false;
    // the step's shared parts
    std::vector<U128> sum_;
    std::string bytes_;
    std::vector<double> gathered_;
    std::vector<std::string> texts_;
    std::atomic<std::uint64_t> tickets_{0};
};

}  // namespace fen
