// team.h — the members that share one render's light paths: MPI ranks (team/mpi_team.h), the
// devices of one process (team/thread_team.h), or one process alone (DESIGN.md §9 "Several
// processes, one image").
//
// Every light path is a function of the seed and its index alone, and every sum on the device is
// of integers, so the work splits exactly: each member traces its share of each pass's path
// indices, and the members' integer sums added together are the one process's sums, bit for bit
// (team/shared_sums.h). A team therefore needs only three collective operations, each called by
// every member in the same order: an exact 128-bit sum, the root's bytes to everyone, and one
// number from each member to everyone (and, for work that is not one render, a shared ticket
// counter and texts gathered to the root). Everything else -- the statistics, the learning, the
// decisions to stop -- each member computes from identical inputs, or takes from the root.
// Invariant: a solo team's operations change nothing, so a render of one member is the plain one.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "util/fixed_point.h"

namespace fen {

class Team {
public:
    virtual ~Team() = default;
    virtual int rank() const = 0;
    virtual int size() const = 0;
    // The rank among the members on this machine: which of its devices this member takes.
    virtual int localRank() const = 0;
    bool root() const { return rank() == 0; }
    // Replaces v, on every member, with the element-wise sum of all members' v (same length
    // everywhere), exactly, modulo 2^128.
    virtual void sum(std::vector<U128>& v) = 0;
    // Replaces `bytes` on every member with the root's.
    virtual void broadcast(std::string& bytes) = 0;
    // Every member's value, in rank order, on every member.
    virtual std::vector<double> gather(double value) = 0;
    // Every member's text, in rank order, on the root (empty elsewhere).
    virtual std::vector<std::string> gatherToRoot(const std::string& text) = 0;
    // The next number of a counter the members share (0, 1, 2, ... over the team's life), each
    // number to one member: dynamic scheduling (`fenestra batch` takes its jobs so). Not a
    // collective: a member calls it alone, whenever it is free.
    virtual std::uint64_t ticket() = 0;
    // What it is, for messages and the JSON: "1 process", "MPI, 3 ranks".
    virtual std::string describe() const = 0;
};

// The team of one: this process alone.
Team& soloTeam();
// The team this process belongs to: soloTeam() unless main() joined another (setProcessTeam).
Team& processTeam();
void setProcessTeam(Team* team);

// This process has made its last collective call of the command: no member waits for it any
// more, so a failure from here on (an output that cannot be written, a batch's failed jobs) ends
// this process alone, with its own status, rather than the whole job.
void markLastCollectiveDone();
bool lastCollectiveDone();

// Derived operations, the same on every team.
// The root's value, on every member.
double fromRoot(Team& team, double value);
bool fromRoot(Team& team, bool value);
// True on every member when it is true on any.
bool anyMember(Team& team, bool value);
// The sum of a count over the members.
std::uint64_t sumOver(Team& team, std::uint64_t value);

}  // namespace fen
