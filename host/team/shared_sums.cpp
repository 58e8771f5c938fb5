// shared_sums.cpp — the members' device sums added after a pass (shared_sums.h).
#include "team/shared_sums.h"

#include <chrono>

#include "util/error.h"

namespace fen {

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Into `w`, whose memory is kept from pass to pass: a film's worth of fresh pages each pass would
// cost as much as reading it.
void readWords(ocl::Context& ctx, const SummedBuffer& b, std::vector<std::uint64_t>& w)
{
    w.resize(b.records * b.recordWords());
    if (!w.empty())
        ctx.queue().enqueueReadBuffer(*b.buffer, CL_TRUE, 0, w.size() * 8, w.data());
}

}  // namespace

void SharedSums::before(std::vector<SummedBuffer> buffers, bool zero)
{
    buffers_ = std::move(buffers);
    zero_ = zero;
    if (team_.size() == 1)
        return;
    before_.resize(buffers_.size());
    now_.resize(buffers_.size());
    const auto t0 = Clock::now();
    for (const SummedBuffer& b : buffers_) {
        for (int f : b.fields)
            if (f != 1 && f != 2)
                throw Error(cat("internal error: a summed field of ", f, " words"));
    }
    for (std::size_t k = 0; k < buffers_.size() && !zero_; ++k)
        readWords(ctx_, buffers_[k], before_[k]);
    const double t = since(t0);
    seconds_ += t;
    deviceSeconds_ += t;
}

void SharedSums::after(std::vector<U128>& extra)
{
    if (team_.size() == 1)
        return;
    const auto t0 = Clock::now();
    // The changes, one 128-bit value a field (a count's in the low word), then `extra`.
    std::vector<std::vector<std::uint64_t>>& now = now_;
    for (std::size_t k = 0; k < buffers_.size(); ++k)
        readWords(ctx_, buffers_[k], now[k]);
    const auto t1 = Clock::now();
    std::size_t fields = extra.size();
    for (std::size_t k = 0; k < buffers_.size(); ++k)
        fields += buffers_[k].records * buffers_[k].fields.size();
    std::vector<U128>& delta = delta_;
    delta.clear();
    delta.reserve(fields);
    for (std::size_t k = 0; k < buffers_.size(); ++k) {
        const std::vector<std::uint64_t>& a = now[k];
        const std::uint64_t* b = zero_ ? nullptr : before_[k].data();  // null: zeros
        const auto was = [b](std::size_t i) { return b ? b[i] : std::uint64_t{0}; };
        for (std::size_t i = 0; i < a.size();)
            for (int f : buffers_[k].fields) {
                if (f == 2)
                    delta.push_back(sub128({a[i], a[i + 1]}, {was(i), was(i + 1)}));
                else
                    delta.push_back({a[i] - was(i), 0});
                i += static_cast<std::size_t>(f);
            }
    }
    const std::size_t fieldCount = delta.size();
    delta.insert(delta.end(), extra.begin(), extra.end());
    const auto t2 = Clock::now();
    team_.sum(delta);
    const auto t3 = Clock::now();
    extra.assign(delta.begin() + static_cast<std::ptrdiff_t>(fieldCount), delta.end());
    // before + the team's changes, back to the device
    std::size_t d = 0;
    for (std::size_t k = 0; k < buffers_.size(); ++k) {
        std::vector<std::uint64_t>& a = now[k];
        const std::uint64_t* b = zero_ ? nullptr : before_[k].data();
        const auto was = [b](std::size_t i) { return b ? b[i] : std::uint64_t{0}; };
        for (std::size_t i = 0; i < a.size();)
            for (int f : buffers_[k].fields) {
                if (f == 2) {
                    const U128 s = add128({was(i), was(i + 1)}, delta[d++]);
                    a[i] = s.lo;
                    a[i + 1] = s.hi;
                } else {
                    a[i] = was(i) + delta[d++].lo;
                }
                i += static_cast<std::size_t>(f);
            }
    }
    const auto t4 = Clock::now();
    for (std::size_t k = 0; k < buffers_.size(); ++k)
        if (!now[k].empty())
            ctx_.queue().enqueueWriteBuffer(*buffers_[k].buffer, CL_TRUE, 0, now[k].size() * 8, now[k].data());
    ++reductions_;
    bytes_ += delta.size() * sizeof(U128);
    const double device = std::chrono::duration<double>(t1 - t0).count() + since(t4);
    const double collective = std::chrono::duration<double>(t3 - t2).count();
    const double all = since(t0);
    seconds_ += all;
    deviceSeconds_ += device;
    collectiveSeconds_ += collective;
    hostSeconds_ += all - device - collective;
}

nlohmann::json SharedSums::report() const
{
    return {{"reductions", reductions_},
            {"bytes", bytes_},
            {"bytes_per_reduction", reductions_ ? static_cast<double>(bytes_) / static_cast<double>(reductions_) : 0.0},
            {"seconds", seconds_},
            {"device_seconds", deviceSeconds_},
            {"host_seconds", hostSeconds_},
            {"collective_seconds", collectiveSeconds_}};
}

}  // namespace fen
