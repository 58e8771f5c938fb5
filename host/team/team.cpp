// team.cpp — the solo team and the operations every team derives from its three (team.h).
#include "team/team.h"

#include <cstring>

namespace fen {

namespace {

class SoloTeam final : public Team {
public:
    int rank() const override { return 0; }
    int size() const override { return 1; }
    int localRank() const override { return 0; }
    void sum(std::vector<U128>&) override {}
    void broadcast(std::string&) override {}
    std::vector<double> gather(double value) override { return {value}; }
    std::vector<std::string> gatherToRoot(const std::string& text) override { return {text}; }
    std::uint64_t ticket() override { return next_++; }
    std::string describe() const override { return "1 process"; }

private:
    std::uint64_t next_ = 0;
};

Team* current = nullptr;
bool lastDone = false;

}  // namespace

Team& soloTeam()
{
    static SoloTeam solo;
    return solo;
}

Team& processTeam() { return current ? *current : soloTeam(); }

void setProcessTeam(Team* team) { current = team; }

void markLastCollectiveDone() { lastDone = true; }

bool lastCollectiveDone() { return lastDone; }

double fromRoot(Team& team, double value)
{
    if (team.size() == 1)
        return value;
    std::string bytes(sizeof value, '\0');
    std::memcpy(bytes.data(), &value, sizeof value);
    team.broadcast(bytes);
    std::memcpy(&value, bytes.data(), sizeof value);
    return value;
}

bool fromRoot(Team& team, bool value) { return fromRoot(team, value ? 1.0 : 0.0) != 0.0; }

std::uint64_t sumOver(Team& team, std::uint64_t value)
{
    std::vector<U128> v{U128{value, 0}};
    team.sum(v);
    return v[0].lo;
}

bool anyMember(Team& team, bool value) { return sumOver(team, value ? 1u : 0u) != 0; }

}  // namespace fen
