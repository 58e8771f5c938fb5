// first_bounce_guide.cpp — the first-bounce guide's learning (first_bounce_guide.h).
#include "scatter/first_bounce_guide.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>

#include "io/state_io.h"
#include "util/error.h"
#include "util/integer_cdf.h"
#include "util/fixed_point.h"

namespace fen {

namespace {

// The device scales v by 2^20 and sums v^2 in 128-bit fixed point: v (what a unit of weight
// delivers, in units of a pixel's solid angle) between about 1e-6 and 1e13 registers and fits.
constexpr int kStatsFixedPointBits = 20;

}  // namespace

void validateGuideOptions(const GuideOptions& o)
{
    if (!(o.share > 0.0 && o.share <= 1.0))
        throw Error(cat("--adaptive-guide-share ", o.share, ": must be in (0, 1] (with 0 a direction the "
                        "guide has not seen light from could never be drawn: bias)"));
    if (o.voxelsAcross < 1 || o.voxelsAcross > 4096)
        throw Error(cat("--adaptive-guide-voxels ", o.voxelsAcross, ": must be in 1..4096"));
    if (o.slots < 1 || o.slots > (1u << 20) || (o.slots & (o.slots - 1)) != 0)
        throw Error(cat("guide slots ", o.slots, " must be a power of 2 up to 2^20"));
    if (!(o.minConnections >= 1.0))
        throw Error(cat("guide minimum contributions ", o.minConnections, " must be at least 1"));
    if (!(o.minGain >= 1.0))
        throw Error(cat("guide minimum gain ", o.minGain, " must be at least 1"));
}

FirstBounceGuide::FirstBounceGuide(ocl::Context& ctx, const GuideOptions& o, glm::dvec3 centre, double radius_m)
    : ctx_(ctx), opt_(o)
{
    validateGuideOptions(opt_);
    const std::uint32_t slots = opt_.enabled ? opt_.slots : 1u;
    const std::size_t boxes = std::size_t{slots} * FEN_GUIDE_BINS;
    const double voxel_m = std::max(radius_m, 1e-6) / opt_.voxelsAcross;
    deviceParams_.lattice = {float(centre.x - radius_m), float(centre.y - radius_m), float(centre.z - radius_m),
                             float(1.0 / voxel_m)};
    deviceParams_.slots = opt_.enabled ? slots : 0u;
    deviceParams_.stats_scale = static_cast<float>(std::ldexp(1.0, kStatsFixedPointBits));
    deviceParams_.alias_shift = 32u - 6u;  // FEN_GUIDE_BINS = 2^6 columns
    static_assert(FEN_GUIDE_BINS == 64, "alias_shift assumes 64 boxes");
    deviceParams_.entries = (slots / 32 + 3) / 4 + 1;  // uint4s of the bitmap, rounded up
    sumSq_.assign(boxes, 0.0);
    connections_.assign(boxes, 0.0);
    rebuild();
    const auto add = [this](std::size_t bytes) {
        deviceBytes_ += bytes;
        return bytes;
    };
    params_ = ctx_.buffer(CL_MEM_READ_ONLY, add(sizeof deviceParams_), "guide parameters", &deviceParams_);
    tables_ = ctx_.buffer(CL_MEM_READ_ONLY, add(tablesHost_.size() * 4), "guide tables", tablesHost_.data());
    stats_ = ctx_.buffer(CL_MEM_READ_WRITE, add(boxes * FEN_GUIDE_STATS_WORDS * 8), "guide statistics");
    clearStats();
}

void FirstBounceGuide::clearStats()
{
    ctx_.queue().enqueueFillBuffer(stats_, cl_ulong(0), 0, sumSq_.size() * FEN_GUIDE_STATS_WORDS * 8);
}

// Every slot's table: learned where it has seen enough, uniform (and marked so) elsewhere.
void FirstBounceGuide::rebuild()
{
    const std::size_t slots = sumSq_.size() / FEN_GUIDE_BINS;
    const std::size_t entries = std::size_t{deviceParams_.entries} * 4;
    tablesHost_.assign(entries + slots * 4 * FEN_GUIDE_BINS, 0u);
    densityHost_.assign(slots * FEN_GUIDE_BINS, 1.0f);
    learnedSlots_ = candidateSlots_ = 0;
    std::vector<double> w(FEN_GUIDE_BINS);
    const auto bits = [](float f) {
        std::uint32_t u;
        std::memcpy(&u, &f, 4);
        return u;
    };
    for (std::size_t s = 0; s < slots; ++s) {
        const double* S = sumSq_.data() + s * FEN_GUIDE_BINS;
        double total = 0.0, seen = 0.0, cosine = 0.0;
        for (int b = 0; b < FEN_GUIDE_BINS; ++b) {
            total += std::sqrt(S[b]);
            cosine += S[b];
            seen += connections_[s * FEN_GUIDE_BINS + b];
        }
        if (!(opt_.enabled && seen >= opt_.minConnections && total > 0.0))
            continue;  // unlearned: the kernels never read its columns
        ++candidateSlots_;
        for (int b = 0; b < FEN_GUIDE_BINS; ++b)
            w[b] = (1.0 - opt_.share) * std::sqrt(S[b]) / total + opt_.share / FEN_GUIDE_BINS;
        const IntegerCdf t = makeIntegerCdf(w);
        if (t.aliasShift != deviceParams_.alias_shift)
            throw Error("guide table: unexpected alias layout");
        double guided = 0.0;  // sum S / d under the new table
        for (int b = 0; b < FEN_GUIDE_BINS; ++b)
            guided += S[b] / (FEN_GUIDE_BINS * t.probability(b));
        if (!(cosine >= opt_.minGain * guided))
            continue;  // too little to gain: the cosine, no table read
        ++learnedSlots_;
        tablesHost_[s / 32] |= 1u << (s % 32);
        float* d = densityHost_.data() + s * FEN_GUIDE_BINS;
        for (int b = 0; b < FEN_GUIDE_BINS; ++b)
            d[b] = static_cast<float>(FEN_GUIDE_BINS * t.probability(b));
        std::uint32_t* col = tablesHost_.data() + entries + s * 4 * FEN_GUIDE_BINS;
        for (int j = 0; j < FEN_GUIDE_BINS; ++j) {
            const std::uint32_t alias = t.alias[2 * j + 1];
            col[4 * j] = t.alias[2 * j];
            col[4 * j + 1] = alias;
            col[4 * j + 2] = bits(d[j]);
            col[4 * j + 3] = bits(d[alias]);
        }
    }
}

void FirstBounceGuide::upload()
{
    ctx_.queue().enqueueWriteBuffer(tables_, CL_TRUE, 0, tablesHost_.size() * 4, tablesHost_.data());
}

void FirstBounceGuide::learn()
{
    if (!opt_.enabled)
        return;
    std::vector<std::uint64_t> raw(sumSq_.size() * FEN_GUIDE_STATS_WORDS);
    ctx_.queue().enqueueReadBuffer(stats_, CL_TRUE, 0, raw.size() * 8, raw.data());
    const double scale = std::ldexp(1.0, -2 * kStatsFixedPointBits);
    for (std::size_t i = 0; i < sumSq_.size(); ++i) {
        const std::uint64_t* w = raw.data() + FEN_GUIDE_STATS_WORDS * i;
        // v^2 d(b), d the density the pass drew the box with: an estimate of the box's S(b).
        sumSq_[i] += fixed128(w + FEN_GUIDE_SUMSQ_LO) * scale * densityHost_[i];
        connections_[i] += static_cast<double>(w[FEN_GUIDE_CONNECTIONS]);
    }
    rebuild();
    upload();
    clearStats();
}

std::vector<double> FirstBounceGuide::probabilities(std::uint32_t slot) const
{
    std::vector<double> p(FEN_GUIDE_BINS);
    for (int b = 0; b < FEN_GUIDE_BINS; ++b)
        p[b] = densityHost_.at(std::size_t{slot} * FEN_GUIDE_BINS + b) / FEN_GUIDE_BINS;
    return p;
}

// Only the boxes that saw light: (index, sum, contributions) triples.
void FirstBounceGuide::save(StateWriter& w) const
{
    std::vector<double> seen;
    for (std::size_t i = 0; i < sumSq_.size(); ++i)
        if (connections_[i] > 0.0 || sumSq_[i] > 0.0) {
            seen.push_back(static_cast<double>(i));
            seen.push_back(sumSq_[i]);
            seen.push_back(connections_[i]);
        }
    w.f64s("guide.boxes", seen);
}

void FirstBounceGuide::load(StateReader& r)
{
    const std::vector<double> seen = r.f64s("guide.boxes", 3 * sumSq_.size());
    if (seen.size() % 3 != 0)
        r.fail("guide.boxes", "not (index, sum, count) triples");
    std::fill(sumSq_.begin(), sumSq_.end(), 0.0);
    std::fill(connections_.begin(), connections_.end(), 0.0);
    for (std::size_t k = 0; k < seen.size(); k += 3) {
        const double i = seen[k];
        if (!(i >= 0.0 && i < static_cast<double>(sumSq_.size())) || !(seen[k + 1] >= 0.0) || !(seen[k + 2] >= 0.0))
            r.fail("guide.boxes", "a box out of range or a negative sum");
        sumSq_[static_cast<std::size_t>(i)] = seen[k + 1];
        connections_[static_cast<std::size_t>(i)] = seen[k + 2];
    }
    rebuild();
    upload();
    clearStats();
}

nlohmann::json FirstBounceGuide::report() const
{
    if (!opt_.enabled)
        return {{"enabled", false}};
    return {{"enabled", true},
            {"slots", opt_.slots},
            {"voxel_m", 1.0 / deviceParams_.lattice.w},
            {"share", opt_.share},
            {"min_connections", opt_.minConnections},
            {"min_gain", opt_.minGain},
            {"candidate_slots", candidateSlots_},
            {"learned_slots", learnedSlots_},
            {"connections", std::accumulate(connections_.begin(), connections_.end(), 0.0)},
            {"memory_bytes", deviceBytes_}};
}

}  // namespace fen
