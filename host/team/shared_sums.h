// shared_sums.h — after every pass, the members' device sums added together, exactly, on every
// member (DESIGN.md §9).
//
// Before a pass each member reads the buffers it is about to add to (before()); after it, it reads
// them again, and the changes -- its own paths' sums alone, whatever the buffers held -- are
// summed over the team (Team::sum, 128-bit) and added to what the buffers held before. Every
// member's buffers then hold the sums of all the pass's paths, as one process that traced them all
// would: integer addition does not care in which order or on which member a path was added, so the
// bytes are the same (the test: tests/team/). Reading the buffers before the pass, rather than
// trusting a copy, lets a strategy clear or rewrite its statistics between passes as it does
// alone. Numbers that are not on the device (the paths a member ran, whether a stop cut its share)
// go along in the same collective.
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
    SharedSums(ocl::Context& ctx, Team& team) : ctx_(ctx), team_(team) {}
    // The buffers a pass is about to add to, as they are now; `zero`: they hold zeros on every
    // member (cleared and not summed since), so nothing is read.
    void before(std::vector<SummedBuffer> buffers, bool zero = false);
    // The pass is done: every buffer holds the team's sums; `extra` is summed alongside.
    void after(std::vector<U128>& extra);
    // The reductions so far: how many, their bytes each way per member, and their wall seconds:
    // in all, and apart the device's reads and writes, the host's differences and additions, and
    // the collective (which includes waiting for the slowest member).
    nlohmann::json report() const;
    double seconds() const { return seconds_; }

private:
    ocl::Context& ctx_;
    Team& team_;
    std::vector<SummedBuffer> buffers_;
    std::vector<std::vector<std::uint64_t>> before_, now_;  // per buffer; kept between passes
    std::vector<U128> delta_;
    bool zero_ = false;
    std::uint64_t reductions_ = 0, bytes_ = 0;
    double seconds_ = 0.0, deviceSeconds_ = 0.0, hostSeconds_ = 0.0, collectiveSeconds_ = 0.0;
};

}  // namespace fen
