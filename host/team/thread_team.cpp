// thread_team.cpp — devices of one process as a team (thread_team.h).
#include "team/thread_team.h"

#include "util/error.h"

namespace fen {

class ThreadTeam::Member final : public Team {
public:
    Member(ThreadTeam& t, int rank) : t_(t), rank_(rank) {}
    int rank() const override { return rank_; }
    int size() const override { return t_.size_; }
    int localRank() const override { return rank_; }
    void sum(std::vector<U128>& v) override
    {
        t_.meet(
            [&] {
                if (t_.sum_.empty())
                    t_.sum_.assign(v.size(), U128{});
                if (t_.sum_.size() != v.size())
                    throw Error("internal error: the devices' sums differ in length");
                for (std::size_t i = 0; i < v.size(); ++i)
                    t_.sum_[i] = add128(t_.sum_[i], v[i]);
            },
            [&] { v = t_.sum_; });
    }
    void broadcast(std::string& bytes) override
    {
        t_.meet([&] { if (rank_ == 0) t_.bytes_ = bytes; }, [&] { if (rank_ != 0) bytes = t_.bytes_; });
    }
    std::vector<double> gather(double value) override
    {
        std::vector<double> all;
        t_.meet(
            [&] {
                t_.gathered_.resize(static_cast<std::size_t>(t_.size_));
                t_.gathered_[static_cast<std::size_t>(rank_)] = value;
            },
            [&] { all = t_.gathered_; });
        return all;
    }
    std::vector<std::string> gatherToRoot(const std::string& text) override
    {
        std::vector<std::string> all;
        t_.meet(
            [&] {
                t_.texts_.resize(static_cast<std::size_t>(t_.size_));
                t_.texts_[static_cast<std::size_t>(rank_)] = text;
            },
            [&] {
                if (rank_ == 0)
                    all = t_.texts_;
            });
        return all;
    }
    std::uint64_t ticket() override { return t_.tickets_++; }
    std::string describe() const override { return cat(t_.size_, " devices"); }

private:
    ThreadTeam& t_;
    int rank_;
};

ThreadTeam::ThreadTeam(int members) : size_(members)
{
    for (int k = 0; k < members; ++k)
        members_.push_back(std::make_unique<Member>(*this, k));
}

ThreadTeam::~ThreadTeam() = default;

Team& ThreadTeam::member(int k) { return *members_[static_cast<std::size_t>(k)]; }

void ThreadTeam::breakTeam()
{
    std::lock_guard<std::mutex> lock(mutex_);
    broken_ = true;
    cv_.notify_all();
}

template <typename Deposit, typename Collect>
void ThreadTeam::meet(Deposit deposit, Collect collect)
{
    std::unique_lock<std::mutex> lock(mutex_);
    const auto fail = [] { throw Error("another device of the render failed"); };
    // the previous step must be empty before this one fills it
    cv_.wait(lock, [&] { return broken_ || left_ == 0; });
    if (broken_)
        fail();
    const std::uint64_t step = generation_;
    deposit();
    if (++arrived_ == size_) {
        arrived_ = 0;
        left_ = size_;
        ++generation_;
        cv_.notify_all();
    } else {
        cv_.wait(lock, [&] { return broken_ || generation_ != step; });
        if (broken_)
            fail();
    }
    collect();
    if (--left_ == 0) {  // the last to leave clears the step's parts
        sum_.clear();
        bytes_.clear();
        gathered_.clear();
        texts_.clear();
        cv_.notify_all();
    }
}

}  // namespace fen
