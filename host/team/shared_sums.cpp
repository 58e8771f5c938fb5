// shared_sums.cpp — the members' device sums added after a pass (shared_sums.h).
#include "team/shared_sums.h"

#include <chrono>

#include "util/error.h"

namespace fen {

namespace {

std::vector<std::uint64_t> readWords(ocl::Context& ctx, const SummedBuffer& b)
{
    std::vector<std::uint64_t> w(b.records * b.recordWords());
    if (!w.empty())
        ctx.queue().enqueueReadBuffer(*b.buffer, CL_TRUE, 0, w.size() * 8, w.data());
    return w;
}

}  // namespace

void SharedSums::before(std::vector<SummedBuffer> buffers)
{
    buffers_ = std::move(buffers);
    before_.clear();
    if (team_.size() == 1)
        return;
    const auto t0 = std::chrono::steady_clock::now();
    for (const SummedBuffer& b : buffers_) {
        for (int f : b.fields)
            if (f != 1 && f != 2)
                throw Error(cat("internal error: a summed field of ", f, " words"));
        before_.push_back(readWords(ctx_, b));
    }
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void SharedSums::after(std::vector<U128>& extra)
{
    if (team_.size() == 1)
        return;
    const auto t0 = std::chrono::steady_clock::now();
    // The changes, one 128-bit value a field (a count's in the low word), then `extra`.
    std::vector<std::vector<std::uint64_t>> now;
    std::vector<U128> delta;
    for (std::size_t k = 0; k < buffers_.size(); ++k) {
        now.push_back(readWords(ctx_, buffers_[k]));
        const std::vector<std::uint64_t>& a = now.back();
        const std::vector<std::uint64_t>& b = before_[k];
        for (std::size_t i = 0; i < a.size();)
            for (int f : buffers_[k].fields) {
                if (f == 2)
                    delta.push_back(sub128({a[i], a[i + 1]}, {b[i], b[i + 1]}));
                else
                    delta.push_back({a[i] - b[i], 0});
                i += static_cast<std::size_t>(f);
            }
    }
    const std::size_t fieldCount = delta.size();
    delta.insert(delta.end(), extra.begin(), extra.end());
    team_.sum(delta);
    extra.assign(delta.begin() + static_cast<std::ptrdiff_t>(fieldCount), delta.end());
    // before + the team's changes, back to the device
    std::size_t d = 0;
    for (std::size_t k = 0; k < buffers_.size(); ++k) {
        std::vector<std::uint64_t>& a = now[k];
        const std::vector<std::uint64_t>& b = before_[k];
        for (std::size_t i = 0; i < a.size();)
            for (int f : buffers_[k].fields) {
                if (f == 2) {
                    const U128 s = add128({b[i], b[i + 1]}, delta[d++]);
                    a[i] = s.lo;
                    a[i + 1] = s.hi;
                } else {
                    a[i] = b[i] + delta[d++].lo;
                }
                i += static_cast<std::size_t>(f);
            }
        if (!a.empty())
            ctx_.queue().enqueueWriteBuffer(*buffers_[k].buffer, CL_TRUE, 0, a.size() * 8, a.data());
    }
    ++reductions_;
    bytes_ += delta.size() * sizeof(U128);
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

nlohmann::json SharedSums::report() const
{
    return {{"reductions", reductions_},
            {"bytes", bytes_},
            {"bytes_per_reduction", reductions_ ? static_cast<double>(bytes_) / static_cast<double>(reductions_) : 0.0},
            {"seconds", seconds_}};
}

}  // namespace fen
