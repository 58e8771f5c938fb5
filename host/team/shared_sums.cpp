// shared_sums.cpp — the members' device sums added after a pass (shared_sums.h).
#include "team/shared_sums.h"

#include <chrono>

#include "cl/launch.h"
#include "util/error.h"

namespace fen {

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The layout as the kernels take it: field count, and bit f set when field f is 128-bit.
cl_uint wideMask(const SummedBuffer& b)
{
    if (b.fields.empty() || b.fields.size() > 32)
        throw Error(cat("internal error: a summed record of ", b.fields.size(), " fields"));
    cl_uint mask = 0;
    for (std::size_t f = 0; f < b.fields.size(); ++f) {
        if (b.fields[f] != 1 && b.fields[f] != 2)
            throw Error(cat("internal error: a summed field of ", b.fields[f], " words"));
        if (b.fields[f] == 2)
            mask |= 1u << f;
    }
    return mask;
}

// `slot` at least `bytes` long (a buffer of 16 bytes or more; kept when long enough).
void ensure(ocl::Context& ctx, cl::Buffer& slot, std::size_t& have, std::size_t bytes, const char* what)
{
    if (have >= bytes && have > 0)
        return;
    have = std::max<std::size_t>(bytes, 16);
    slot = ctx.buffer(CL_MEM_READ_WRITE, have, what);
}

}  // namespace

SharedSums::SharedSums(ocl::Context& ctx, Team& team) : ctx_(ctx), team_(team)
{
    if (team_.size() == 1)
        return;
    cl::Program program = ctx_.program("team_sums.cl");
    difference_ = cl::Kernel(program, "team_difference");
    add_ = cl::Kernel(program, "team_add");
}

void SharedSums::before(std::vector<SummedBuffer> buffers, bool zero)
{
    buffers_ = std::move(buffers);
    zero_ = zero;
    if (team_.size() == 1)
        return;
    const auto t0 = Clock::now();
    scratch_.resize(std::max(scratch_.size(), buffers_.size()));
    for (std::size_t k = 0; k < buffers_.size(); ++k) {
        const SummedBuffer& b = buffers_[k];
        wideMask(b);  // checks the layout
        const std::size_t bytes = b.records * b.recordWords() * 8;
        if (zero_ || bytes == 0)
            continue;
        ensure(ctx_, scratch_[k].before, scratch_[k].beforeBytes, bytes, "a team's copy of a summed buffer");
        ctx_.queue().enqueueCopyBuffer(*b.buffer, scratch_[k].before, 0, 0, bytes);
    }
    ctx_.queue().finish();
    const double t = since(t0);
    seconds_ += t;
    deviceSeconds_ += t;
}

void SharedSums::after(std::vector<U128>& extra)
{
    if (team_.size() == 1)
        return;
    const auto t0 = Clock::now();
    auto& q = ctx_.queue();
    // The differences: one 128-bit value a field, every buffer's in turn, then `extra`.
    std::size_t fields = extra.size();
    for (const SummedBuffer& b : buffers_)
        fields += b.records * b.fields.size();
    delta_.resize(fields);
    // every buffer with fields, its scratch, its field count and where its fields start in delta_
    const auto eachBuffer = [&](const auto& step) {
        std::size_t at = 0;
        for (std::size_t k = 0; k < buffers_.size(); ++k) {
            const std::size_t n = buffers_[k].records * buffers_[k].fields.size();
            if (n > 0)
                step(buffers_[k], scratch_[k], n, delta_.data() + at);
            at += n;
        }
        return at;
    };
    const std::size_t at = eachBuffer([&](const SummedBuffer& b, Scratch& s, std::size_t n, U128* out) {
        ensure(ctx_, s.delta, s.deltaBytes, n * 16, "a team's differences of a summed buffer");
        ensure(ctx_, s.before, s.beforeBytes, 16, "a team's copy of a summed buffer");  // bound when zero_
        ocl::setKernelArgsFrom(difference_, 0, *b.buffer, s.before, static_cast<cl_uint>(b.records),
                               static_cast<cl_uint>(b.fields.size()), wideMask(b), cl_uint(zero_ ? 1 : 0), s.delta);
        ocl::launch(ctx_, difference_, "team_difference", b.records);
        q.enqueueReadBuffer(s.delta, CL_FALSE, 0, n * 16, out);
    });
    std::copy(extra.begin(), extra.end(), delta_.begin() + static_cast<std::ptrdiff_t>(at));
    q.finish();
    const auto t1 = Clock::now();
    team_.sum(delta_);
    const auto t2 = Clock::now();
    extra.assign(delta_.begin() + static_cast<std::ptrdiff_t>(at), delta_.end());
    // before + the team's sums, on the device
    eachBuffer([&](const SummedBuffer& b, Scratch& s, std::size_t n, const U128* sums) {
        q.enqueueWriteBuffer(s.delta, CL_FALSE, 0, n * 16, sums);
        ocl::setKernelArgsFrom(add_, 0, *b.buffer, s.before, s.delta, static_cast<cl_uint>(b.records),
                               static_cast<cl_uint>(b.fields.size()), wideMask(b), cl_uint(zero_ ? 1 : 0));
        ocl::launch(ctx_, add_, "team_add", b.records);
    });
    q.finish();
    ++reductions_;
    bytes_ += delta_.size() * sizeof(U128);
    const double collective = std::chrono::duration<double>(t2 - t1).count();
    const double all = since(t0);
    seconds_ += all;
    deviceSeconds_ += all - collective;
    collectiveSeconds_ += collective;
}

nlohmann::json SharedSums::report() const
{
    return {{"reductions", reductions_},
            {"bytes", bytes_},
            {"bytes_per_reduction", reductions_ ? static_cast<double>(bytes_) / static_cast<double>(reductions_) : 0.0},
            {"seconds", seconds_},
            {"device_seconds", deviceSeconds_},
            {"collective_seconds", collectiveSeconds_}};
}

}  // namespace fen
