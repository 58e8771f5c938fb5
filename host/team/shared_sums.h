// shared_sums.h — after every pass, the members' device sums added together, exactly, on every
// member (DESIGN.md §9).
//
// Before a pass each member copies the buffers it is about to add to, on the device (before());
// after it, a kernel takes the differences -- its own paths' sums alone, whatever the buffers held
// -- as one 128-bit value per field (kernels/team_sums.cl), the host reads them, sums them over the
// team (Team::sum) and writes the sums back, and a second kernel adds them to the copies. Every
// member's buffers then hold the sums of all the pass's paths, as one process that traced them all
// would: integer addition does not care in which order or on which member a path was added, so the
// bytes are the same (tests/e2e/team_test.cpp). Copying before the pass, rather than trusting what
// the last sum left, lets a strategy clear or rewrite its statistics between passes as it does
// alone. Numbers that are not on the device (the paths a member ran, whether a stop cut its share)
// go along in the same collective. Each buffer costs twice its bytes more on the device (the copy
// and the differences), allocated the first time it is summed; a team of one does nothing.
#pragma once

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "cl/context.h"
#include "team/summed_buffer.h"
#include "team/team.h"

namespace fen {

class SharedSums {
public:
    SharedSums(ocl::Context& ctx, Team& team);
    // The buffers a pass is about to add to, copied as they are now; `zero`: they hold zeros on
    // every member (cleared and not summed since), so nothing is copied.
    void before(std::vector<SummedBuffer> buffers, bool zero = false);
    // The pass is done: every buffer holds the team's sums; `extra` is summed alongside.
    void after(std::vector<U128>& extra);
    // The reductions so far: how many, their bytes each way per member, and their wall seconds:
    // in all, and apart the device's part (copies, the two kernels, reading the differences and
    // writing the sums), and the collective (which includes waiting for the slowest member).
    nlohmann::json report() const;

private:
    // A buffer's copy and differences on the device, grown as needed.
    struct Scratch {
        cl::Buffer before, delta;
        std::size_t beforeBytes = 0, deltaBytes = 0;
    };
    ocl::Context& ctx_;
    Team& team_;
    cl::Kernel difference_, add_;
    std::vector<SummedBuffer> buffers_;
    std::vector<Scratch> scratch_;
    std::vector<U128> delta_;  // the differences, then the sums, of every buffer and `extra`
    bool zero_ = false;
    std::uint64_t reductions_ = 0, bytes_ = 0;
    double seconds_ = 0.0, deviceSeconds_ = 0.0, collectiveSeconds_ = 0.0;
};

}  // namespace fen
