// first_bounce_guide.cpp — the first-bounce guide's trees, learning and tables (first_bounce_guide.h).
#include "scatter/first_bounce_guide.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <functional>
#include <limits>
#include <numeric>

#include "io/state_io.h"
#include "shared/fen_render.h"
#include "util/error.h"
#include "util/integer_cdf.h"
#include "util/fixed_point.h"
#include "util/fnv.h"
#include "util/in_shares.h"

namespace fen {

namespace {

// The device scales v by 2^20 and sums v^2 in 128-bit fixed point: v (what a unit of weight
// delivers, in units of a pixel's solid angle) between about 1e-6 and 1e13 registers and fits.
constexpr int kStatsFixedPointBits = 20;
constexpr int kInitialNodes = 21;   // (4^3 - 1) / 3: the nodes of a full tree of depth 3
constexpr int kInitialLeaves = 64;  // 4^FEN_GUIDE_INITIAL_DEPTH
static_assert(FEN_GUIDE_INITIAL_DEPTH == 3, "kInitialNodes, kInitialLeaves assume depth 3");
static_assert(FEN_GUIDE_MAX_DEPTH <= 14, "a leaf's corner has 14 bits per axis");
// Device bytes per leaf: its statistics, its entry, up to two alias columns, a third of a node.
constexpr double kBytesPerLeaf = 8.0 * FEN_GUIDE_STATS_WORDS + 8.0 + 16.0 + 16.0 / 3.0;
constexpr double kMiB = 1024.0 * 1024.0;
constexpr std::size_t kSavedPerLeaf = 2;  // a leaf's totals in a checkpoint: Leaf::totals()
constexpr std::size_t kSavedPerWindow = 3;  // a slot's window totals in a checkpoint: WindowTotals::totals()
// Device bytes per slot with weight windows: its statistics (with the aim's sums) and its window word.
constexpr double kWindowBytesPerSlot = 8.0 * FEN_GUIDE_WINDOW_WORDS + 4.0;

// Voxels along each side of the lattice cube (side 2R): the power of 2 at or above 2 voxelsAcross.
std::uint32_t latticeCells(int voxelsAcross)
{
    std::uint32_t c = 1;
    while (c < 2u * static_cast<std::uint32_t>(voxelsAcross))
        c *= 2;
    return c;
}

std::uint32_t floatBits(float f)
{
    std::uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

}  // namespace

bool FirstBounceGuide::isInitial(const Tree& t)
{
    return t.nodes.size() == kInitialNodes &&
           std::all_of(t.leaves.begin(), t.leaves.end(), [](const Leaf& l) { return l.depth == FEN_GUIDE_INITIAL_DEPTH; });
}

void validateGuideOptions(const GuideOptions& o)
{
    if (!(o.share > 0.0 && o.share <= 1.0))
        throw Error(cat("--adaptive-guide-share ", o.share, ": must be in (0, 1] (with 0 a direction the "
                        "guide has not seen light from could never be drawn: bias)"));
    if (o.voxelsAcross < 1 || o.voxelsAcross > 16)
        throw Error(cat("--adaptive-guide-voxels ", o.voxelsAcross, ": must be in 1..16"));
    if (!(o.spatialSplitConnections >= 1.0))
        throw Error(cat("--adaptive-guide-space-split ", o.spatialSplitConnections, ": must be at least 1 contribution"));
    if (o.maxSpatialDepth < 0 || o.maxSpatialDepth > 30)
        throw Error(cat("guide spatial depth ", o.maxSpatialDepth, " must be in 0..30"));
    if (!(o.minConnections >= 1.0))
        throw Error(cat("--adaptive-guide-min-contributions ", o.minConnections, ": must be at least 1"));
    if (!(o.minGain >= 1.0))
        throw Error(cat("--adaptive-guide-min-gain ", o.minGain, ": must be at least 1 (below 1 a table that "
                        "promises more variance than the cosine would steer)"));
    if (o.maxDepth < FEN_GUIDE_INITIAL_DEPTH || o.maxDepth > FEN_GUIDE_MAX_DEPTH)
        throw Error(cat("--adaptive-guide-depth ", o.maxDepth, ": must be in ", FEN_GUIDE_INITIAL_DEPTH, "..",
                        FEN_GUIDE_MAX_DEPTH, " (", FEN_GUIDE_INITIAL_DEPTH, ": the initial 8 x 8 leaves, never split)"));
    if (!(o.splitShare > 0.0 && o.splitShare <= 1.0))
        throw Error(cat("--adaptive-guide-split ", o.splitShare, ": must be in (0, 1]"));
    if (!(o.minLeafConnections >= 1.0))
        throw Error(cat("guide minimum contributions per leaf ", o.minLeafConnections, " must be at least 1"));
    if (!(o.windowLater >= 1.0 && o.windowLater <= 64.0))
        throw Error(cat("--adaptive-window-later ", o.windowLater, ": must be in [1, 64] (1: the first vertex's windows)"));
    if (o.windowSplitMax < 2 || o.windowSplitMax > FEN_MAX_BRANCHES)
        throw Error(cat("--adaptive-window-split ", o.windowSplitMax, ": must be in 2..", FEN_MAX_BRANCHES));
    if (!(o.windowMinSurvival > 0.0 && o.windowMinSurvival <= 1.0))
        throw Error(cat("--adaptive-window-survival ", o.windowMinSurvival, ": must be in (0, 1] (with 0 a path "
                        "the windows cull could never survive: bias)"));
    if (!(o.windowMinVisits >= 1.0))
        throw Error(cat("window minimum visits ", o.windowMinVisits, " must be at least 1"));
    // The trees' initial 8 x 8 leaves must fit, with room to refine.
    const double cells = latticeCells(o.voxelsAcross), slots = FEN_GUIDE_SIDES * cells * cells * cells;
    const double initialMiB =
        (slots * (16.0 + 16.0 * kInitialNodes + kBytesPerLeaf * kInitialLeaves) + 4.0 * cells * cells * cells) / kMiB;
    if (!(o.memoryMiB >= 2.0 * initialMiB && o.memoryMiB <= 16384.0)) {
        // too little for more voxels than the default: named by the option the user more likely changed
        if (o.memoryMiB <= 16384.0 && o.voxelsAcross != GuideOptions{}.voxelsAcross)
            throw Error(cat("--adaptive-guide-voxels ", o.voxelsAcross, ": needs --adaptive-guide-memory ",
                            std::ceil(2.0 * initialMiB), " or more (twice what its initial trees take; ",
                            o.memoryMiB, " MiB given)"));
        throw Error(cat("--adaptive-guide-memory ", o.memoryMiB, ": must be in ", std::ceil(2.0 * initialMiB),
                        "..16384 MiB (at least twice what the initial trees of ", o.voxelsAcross,
                        " voxels across the radius take)"));
    }
}

// Quadrant q (bit 0: the upper half in x, bit 1 in y) of the square of side 2^-depth at (x0, y0),
// in 2^-FEN_GUIDE_MAX_DEPTH units: a leaf one level deeper, with no statistics.
FirstBounceGuide::Leaf FirstBounceGuide::quadrant(std::uint32_t x0, std::uint32_t y0, std::uint32_t depth,
                                                  std::uint32_t q)
{
    const std::uint32_t half = 1u << (FEN_GUIDE_MAX_DEPTH - depth - 1);
    Leaf l;
    l.x0 = x0 + (q & 1u) * half;
    l.y0 = y0 + (q >> 1) * half;
    l.depth = depth + 1;
    return l;
}

FirstBounceGuide::Tree FirstBounceGuide::initialTree()
{
    Tree t;
    // Full to FEN_GUIDE_INITIAL_DEPTH, in the order the refinement copies trees (depth first).
    std::function<std::int32_t(std::uint32_t, std::uint32_t, std::uint32_t)> node =
        [&](std::uint32_t x0, std::uint32_t y0, std::uint32_t depth) {
            const auto at = static_cast<std::int32_t>(t.nodes.size());
            t.nodes.push_back({});
            for (std::uint32_t q = 0; q < 4; ++q) {
                const Leaf l = quadrant(x0, y0, depth, q);
                std::int32_t c;
                if (l.depth < FEN_GUIDE_INITIAL_DEPTH) {
                    c = node(l.x0, l.y0, l.depth);
                } else {
                    c = ~static_cast<std::int32_t>(t.leaves.size());
                    t.leaves.push_back(l);
                }
                t.nodes[at][q] = c;
            }
            return at;
        };
    node(0, 0, 0);
    return t;
}

FirstBounceGuide::FirstBounceGuide(ocl::Context& ctx, const GuideOptions& o, glm::dvec3 centre, double radius_m)
    : ctx_(ctx), opt_(o)
{
    validateGuideOptions(opt_);
    const double r = std::max(radius_m, 1e-6);
    deviceParams_.lattice = {float(centre.x - r), float(centre.y - r), float(centre.z - r), float(1.0 / (2.0 * r))};
    deviceParams_.stats_scale = static_cast<float>(std::ldexp(1.0, kStatsFixedPointBits));
    side_m_ = 2.0 * r;
    std::size_t voxels = 1;
    if (opt_.enabled) {
        cells_ = latticeCells(opt_.voxelsAcross);
        voxels = std::size_t{cells_} * cells_ * cells_;
        for (std::uint32_t v = 0; v < voxels; ++v) {
            voxelWord_.push_back(FEN_GUIDE_LEAF | v);
            SpatialLeaf l;
            l.voxel = v;
            spatialLeaves_.push_back(l);
        }
        trees_.assign(FEN_GUIDE_SIDES * voxels, initialTree());
        // Per leaf: its own bytes (with weight windows, its slot's word too), and its share of a
        // slot's record, window statistics and a spatial node when every slot has at least the
        // initial 64 leaves.
        const double perLeaf = kBytesPerLeaf + (opt_.window ? 4.0 + kWindowBytesPerSlot / kInitialLeaves : 0.0) +
                               (16.0 + 8.0 / FEN_GUIDE_SIDES) / kInitialLeaves;
        leafCapacity_ = static_cast<std::size_t>((opt_.memoryMiB * kMiB - 4.0 * voxels) / perLeaf);
        slotCapacity_ = std::max(trees_.size(), leafCapacity_ / kInitialLeaves);
        spatialCapacity_ = slotCapacity_ / FEN_GUIDE_SIDES;
        nodeCapacity_ = leafCapacity_ / 3 + slotCapacity_;
        columnCapacity_ = 2 * leafCapacity_;
    } else {
        // placeholders the kernels never read
        slotCapacity_ = spatialCapacity_ = leafCapacity_ = nodeCapacity_ = columnCapacity_ = 1;
        voxelWord_.assign(1, FEN_GUIDE_LEAF);
    }
    deviceParams_.cells = cells_;
    deviceParams_.every_vertex = opt_.enabled && opt_.everyVertex ? 1u : 0u;
    deviceParams_.voxels_at = static_cast<std::uint32_t>(4 * slotCapacity_);
    deviceParams_.spatial_at = static_cast<std::uint32_t>(deviceParams_.voxels_at + voxels);
    const std::size_t nodesAt = deviceParams_.spatial_at + 2 * spatialCapacity_;
    const std::size_t tableWords = nodesAt + 4 * nodeCapacity_ + 2 * leafCapacity_ + 2 * columnCapacity_;
    if (tableWords + slotCapacity_ + leafCapacity_ >= (std::size_t{1} << 32))
        throw Error(cat("--adaptive-guide-memory ", opt_.memoryMiB, ": the tables would pass 2^32 words"));
    deviceParams_.nodes_at = static_cast<std::uint32_t>(nodesAt);
    deviceParams_.leaves_at = static_cast<std::uint32_t>(deviceParams_.nodes_at + 4 * nodeCapacity_);
    deviceParams_.columns_at = static_cast<std::uint32_t>(deviceParams_.leaves_at + 2 * leafCapacity_);
    if (opt_.enabled && opt_.window) {
        deviceParams_.windows_at = static_cast<std::uint32_t>(deviceParams_.columns_at + 2 * columnCapacity_);
        deviceParams_.window_min_survival = static_cast<float>(opt_.windowMinSurvival);
        deviceParams_.window_split_max = static_cast<std::uint32_t>(opt_.windowSplitMax);
        deviceParams_.window_power = opt_.windowRule == GuideOptions::WindowRule::Moment ? 2u : 1u;
        deviceParams_.leaf_slots_at = static_cast<std::uint32_t>(deviceParams_.windows_at + slotCapacity_);
        deviceParams_.window_later = opt_.windowEveryVertex ? static_cast<float>(opt_.windowLater) : 0.0f;
        deviceParams_.aim_sums = opt_.aimSums ? 1u : 0u;
    }
    // with weight windows: a word per slot (its window) and per leaf (its slot)
    const std::size_t windowWords = deviceParams_.windows_at ? slotCapacity_ + leafCapacity_ : 0;
    rebuild();
    const auto add = [this](std::size_t bytes) {
        deviceBytes_ += bytes;
        return bytes;
    };
    params_ = ctx_.buffer(CL_MEM_READ_ONLY, add(sizeof deviceParams_), "guide parameters", &deviceParams_);
    tables_ = ctx_.buffer(CL_MEM_READ_ONLY, add((tableWords + windowWords) * 4), "guide tables");
    stats_ = ctx_.buffer(CL_MEM_READ_WRITE, add(leafCapacity_ * FEN_GUIDE_STATS_WORDS * 8), "guide statistics");
    windowStats_ = ctx_.buffer(CL_MEM_READ_WRITE, add((windowWords ? slotCapacity_ : 1) * FEN_GUIDE_WINDOW_WORDS * 8),
                               "guide window statistics");
    upload();
    clearStats();
}

static_assert(FEN_GUIDE_SUMSQ_LO == 0 && FEN_GUIDE_CONNECTIONS == 2 && FEN_GUIDE_STATS_WORDS == 3,
              "a leaf's statistics as summed() describes them: a 128-bit sum and a count");
static_assert(FEN_GUIDE_DELIVERED_LO == 0 && FEN_GUIDE_ARRIVED_LO == 2 && FEN_GUIDE_VISITS == 4 &&
                  FEN_GUIDE_MIXED_SQ_LO == 5 && FEN_GUIDE_AIMED_SQ_LO == 7 && FEN_GUIDE_WINDOW_WORDS == 9,
              "a slot's window statistics as windowSummed() describes them: two 128-bit sums, a count and two "
              "128-bit sums");

void FirstBounceGuide::clearStats()
{
    ctx_.queue().enqueueFillBuffer(stats_, cl_ulong(0), 0,
                                   std::max<std::size_t>(leafCount_, 1) * FEN_GUIDE_STATS_WORDS * 8);
    if (deviceParams_.windows_at)
        ctx_.queue().enqueueFillBuffer(windowStats_, cl_ulong(0), 0,
                                       std::max<std::size_t>(trees_.size(), 1) * FEN_GUIDE_WINDOW_WORDS * 8);
}

// Splits, in every slot whose table will steer, each leaf that held more than splitShare of its
// slot's m = sqrt(S A) in the pass just read (`pass`: per slot and leaf, that pass's S and
// contributions) and saw minLeafConnections contributions in it, largest shares first while the
// capacity lasts. Marks those slots in promising_. Only the pass's own
// statistics decide: the quarters a split leaf hands its children are a guess, not evidence of
// more detail. Returns the splits made.
std::size_t FirstBounceGuide::refine(const PassStats& pass)
{
    struct Candidate {
        double share;
        std::uint32_t slot;
        std::int32_t leaf;
    };
    promising_.assign(trees_.size(), 0);
    // Each slot lists its own candidates (the slots in shares over the threads); in slot order
    // they make one list, which the sort below orders by a key that ties nowhere.
    std::vector<std::vector<Candidate>> found(trees_.size());
    inShares(trees_.size(), [&](std::size_t s0, std::size_t s1) {
        for (std::size_t s = s0; s < s1; ++s) {
            const Tree& t = trees_[s];
            const double* sumSq = pass.sumSq.data() + pass.first[s];
            const double* connections = pass.connections.data() + pass.first[s];
            double total = 0.0;
            for (std::size_t i = 0; i < t.leaves.size(); ++i)
                total += std::sqrt(sumSq[i] * t.leaves[i].area());
            if (!(total > 0.0))
                continue;
            // Only where the table will steer (rebuild()'s test, before the integer rounding): a
            // finer tree where the cosine is kept would cost its descents and buy nothing.
            const std::vector<double> p = mixture(t);
            if (p.empty() || !steers(t, p))
                continue;
            promising_[s] = 1;
            for (std::size_t i = 0; i < t.leaves.size(); ++i) {
                const Leaf& l = t.leaves[i];
                const double share = std::sqrt(sumSq[i] * l.area()) / total;
                if (static_cast<int>(l.depth) < opt_.maxDepth && connections[i] >= opt_.minLeafConnections &&
                    share > opt_.splitShare)
                    found[s].push_back({share, static_cast<std::uint32_t>(s), static_cast<std::int32_t>(i)});
            }
        }
    }, 64);
    std::vector<Candidate> cand;
    for (const auto& f : found)
        cand.insert(cand.end(), f.begin(), f.end());
    std::sort(cand.begin(), cand.end(), [](const Candidate& a, const Candidate& b) {
        return a.share != b.share ? a.share > b.share : (a.slot != b.slot ? a.slot < b.slot : a.leaf < b.leaf);
    });
    const std::size_t room = std::min((leafCapacity_ - leafCount_) / 3, nodeCapacity_ - nodeCount());
    const std::size_t made = std::min(room, cand.size());
    deferredSplits_ = cand.size() - made;
    std::vector<std::vector<char>> split(trees_.size());
    for (std::size_t k = 0; k < made; ++k) {
        auto& mark = split[cand[k].slot];
        mark.resize(trees_[cand[k].slot].leaves.size(), 0);
        mark[static_cast<std::size_t>(cand[k].leaf)] = 1;
    }
    inShares(trees_.size(), [&](std::size_t s0, std::size_t s1) {
        for (std::size_t s = s0; s < s1; ++s)
            if (!split[s].empty())
                splitLeaves(trees_[s], split[s]);
    }, 64);
    leafCount_ += 3 * made;
    return made;
}

// The tree with every leaf marked in `split` made four, each with a quarter of its statistics: the
// uniform guess until the next pass shows more.
void FirstBounceGuide::splitLeaves(Tree& tree, const std::vector<char>& split)
{
    const Tree old = std::move(tree);
    Tree t;
    t.window = old.window;
    std::function<std::int32_t(std::int32_t)> copy = [&](std::int32_t n) {
        const auto at = static_cast<std::int32_t>(t.nodes.size());
        t.nodes.push_back({});
        for (int q = 0; q < 4; ++q) {
            const std::int32_t c = old.nodes[static_cast<std::size_t>(n)][q];
            std::int32_t made_c;
            if (c >= 0) {
                made_c = copy(c);
            } else if (!split[static_cast<std::size_t>(~c)]) {
                made_c = ~static_cast<std::int32_t>(t.leaves.size());
                t.leaves.push_back(old.leaves[static_cast<std::size_t>(~c)]);
            } else {
                const Leaf& p = old.leaves[static_cast<std::size_t>(~c)];
                made_c = static_cast<std::int32_t>(t.nodes.size());
                t.nodes.push_back({});
                for (std::uint32_t k = 0; k < 4; ++k) {
                    Leaf l = p;
                    l.scaleTotals(0.25);
                    const Leaf q = quadrant(p.x0, p.y0, p.depth, k);
                    l.x0 = q.x0, l.y0 = q.y0, l.depth = q.depth;
                    t.nodes[static_cast<std::size_t>(made_c)][k] = ~static_cast<std::int32_t>(t.leaves.size());
                    t.leaves.push_back(l);
                }
            }
            t.nodes[static_cast<std::size_t>(at)][q] = made_c;
        }
        return at;
    };
    copy(0);
    tree = std::move(t);
}

// The slot's table before the integer rounding: P(b) = (1 - share) m(b) / sum m + share A(b), with
// m = sqrt(S A); empty while it has seen fewer than minConnections contributions or none with light.
std::vector<double> FirstBounceGuide::mixture(const Tree& t) const
{
    double seen = 0.0, total = 0.0;
    for (const Leaf& l : t.leaves) {
        seen += l.connections;
        total += std::sqrt(l.sumSq * l.area());
    }
    if (!(seen >= opt_.minConnections && total > 0.0))
        return {};
    std::vector<double> p;
    for (const Leaf& l : t.leaves)
        p.push_back((1.0 - opt_.share) * std::sqrt(l.sumSq * l.area()) / total + opt_.share * l.area());
    return p;
}

// Whether drawing the slot's leaves with probabilities p cuts the second moment sum S / d, d = p / A,
// at least minGain times against the cosine's sum S.
bool FirstBounceGuide::steers(const Tree& t, const std::vector<double>& p) const
{
    double cosine = 0.0, guided = 0.0;
    for (std::size_t b = 0; b < p.size(); ++b) {
        cosine += t.leaves[b].sumSq;
        guided += t.leaves[b].sumSq * t.leaves[b].area() / p[b];
    }
    return cosine >= opt_.minGain * guided;
}

// Every slot's table: learned where it has seen enough and the table promises minGain, the
// cosine elsewhere; then the flat layout of fen_guide.h.
void FirstBounceGuide::rebuild()
{
    // Each slot's table on its own (the slots in shares over the machine's threads).
    std::vector<char> candidate(trees_.size(), 0);
    inShares(trees_.size(), [&](std::size_t s0, std::size_t s1) {
        for (std::size_t s = s0; s < s1; ++s) {
            Tree& t = trees_[s];
            t.learned = false;
            t.alias.clear();
            for (Leaf& l : t.leaves)
                l.density = 1.0f;
            const std::vector<double> w = mixture(t);
            if (w.empty())
                continue;  // the cosine: the kernels read only the tree, for the record
            candidate[s] = 1;
            const IntegerCdf cdf = makeIntegerCdf(w);
            std::vector<double> realised(w.size());
            for (std::size_t b = 0; b < w.size(); ++b)
                realised[b] = cdf.probability(b);
            if (!steers(t, realised))
                continue;  // too little to gain: the cosine, no table read
            t.learned = true;
            t.aliasShift = cdf.aliasShift;
            t.alias = cdf.alias;
            for (std::size_t b = 0; b < w.size(); ++b)
                t.leaves[b].density = static_cast<float>(realised[b] / t.leaves[b].area());
        }
    }, 64);

    // The sections of fen_guide.h, each as long as it is used; upload() puts them at their offsets.
    deviceParams_.slots = static_cast<std::uint32_t>(trees_.size());
    records_.assign(4 * trees_.size(), 0u);
    spatialWords_.clear();
    for (const auto& n : spatialNodes_)
        spatialWords_.insert(spatialWords_.end(), {n[0], n[1]});
    // Each slot's offsets in turn (records 0-2) and the counts, then its words in the threads' shares.
    learnedSlots_ = candidateSlots_ = maxDepthSeen_ = 0;
    std::size_t nodes = 0, leaves = 0, columns = 0;
    for (std::size_t s = 0; s < trees_.size(); ++s) {
        const Tree& t = trees_[s];
        std::uint32_t* rec = records_.data() + 4 * s;
        rec[0] = static_cast<std::uint32_t>(nodes);
        rec[1] = static_cast<std::uint32_t>(leaves);
        rec[2] = static_cast<std::uint32_t>(columns / 2);
        nodes += t.nodes.size();
        leaves += t.leaves.size();
        columns += t.learned ? t.alias.size() : 0;
        for (const Leaf& l : t.leaves)
            maxDepthSeen_ = std::max(maxDepthSeen_, l.depth);
        candidateSlots_ += candidate[s];
        learnedSlots_ += t.learned;
    }
    leafCount_ = leaves;
    nodeWords_.resize(4 * nodes);
    leafWords_.resize(2 * leaves);
    columnWords_.resize(columns);
    leafSlotWords_.resize(deviceParams_.windows_at ? leaves : 0);
    inShares(trees_.size(), [&](std::size_t s0, std::size_t s1) {
        for (std::size_t s = s0; s < s1; ++s) {
            const Tree& t = trees_[s];
            std::uint32_t* rec = records_.data() + 4 * s;
            rec[3] = (t.learned ? FEN_GUIDE_LEARNED | t.aliasShift : 0u) | (isInitial(t) ? FEN_GUIDE_INITIAL : 0u);
            std::uint32_t* node = nodeWords_.data() + 4 * std::size_t{rec[0]};
            for (const auto& n : t.nodes)
                for (int q = 0; q < 4; ++q)
                    *node++ = n[q] >= 0 ? rec[0] + static_cast<std::uint32_t>(n[q])
                                        : FEN_GUIDE_LEAF | (rec[1] + static_cast<std::uint32_t>(~n[q]));
            std::uint32_t* leaf = leafWords_.data() + 2 * std::size_t{rec[1]};
            for (const Leaf& l : t.leaves) {
                *leaf++ = floatBits(l.density);
                *leaf++ = l.x0 | (l.y0 << 14) | (l.depth << 28);
            }
            if (t.learned)
                std::copy(t.alias.begin(), t.alias.end(), columnWords_.begin() + 2 * std::ptrdiff_t{rec[2]});
            if (deviceParams_.windows_at)
                std::fill_n(leafSlotWords_.begin() + std::ptrdiff_t{rec[1]}, t.leaves.size(), static_cast<std::uint32_t>(s));
        }
    }, 64);
    rebuildWindows();
    if (nodeWords_.size() > 4 * nodeCapacity_ || leafWords_.size() > 2 * leafCapacity_ ||
        columnWords_.size() > 2 * columnCapacity_ || trees_.size() > slotCapacity_ ||
        spatialNodes_.size() > spatialCapacity_)
        throw Error("guide tables: beyond the capacity they were sized for");  // refine() keeps within
}

// The weight windows (fen_guide.h), per slot from its totals (sums at the window scale S, the squares
// at S^2, each of the power the rule needs; a = a path's arriving luminance over A_pix, C a
// contribution it made after):
//  - rule Mean: the adjoint J = sum C / sum a -- what a unit of arriving weight delivers from
//    then on, on average -- and the target T = sum C / visits over all slots; w = T / J, the
//    arriving weight expected to deliver T;
//  - rule Moment: M = sum C^2 / sum a^2 -- the second moment of what a unit of arriving weight
//    delivers, contribution by contribution (each lands in its own pixel, so it is what the
//    image's variance adds up) -- and tau^2 = sum C^2 / visits; w = tau / sqrt(M), the arriving
//    weight whose root second moment is the average path's: splitting and culling then even out
//    what paths add to the variance, not to the mean (a path that rarely delivers a great deal is
//    not culled for its small mean).
// w comes out in the units of a, which the device compares a path's with. A slot seen fewer than windowMinVisits times has
// none (0: the fixed rules); one seen that often that never delivered gets FLT_MAX (every path
// there culled down to windowMinSurvival).
void FirstBounceGuide::rebuildWindows()
{
    windowWords_.clear();
    windowSlots_ = 0;
    windowTarget_ = 0.0;
    deviceParams_.window_min = 0.0f;
    if (!deviceParams_.windows_at)
        return;
    const bool moment = opt_.windowRule == GuideOptions::WindowRule::Moment;
    double allDelivered = 0.0, allVisits = 0.0;
    for (const Tree& t : trees_) {
        allDelivered += t.window.delivered;
        allVisits += t.window.visits;
    }
    windowWords_.assign(trees_.size(), 0u);
    if (!(allDelivered > 0.0))
        return;
    windowTarget_ = allDelivered / allVisits;  // T S, or tau^2 S^2
    for (std::size_t s = 0; s < trees_.size(); ++s) {
        const Tree& t = trees_[s];
        if (t.window.visits < opt_.windowMinVisits || !(t.window.arrived > 0.0))
            continue;
        const double ratio = t.window.delivered > 0.0 ? windowTarget_ * t.window.arrived / t.window.delivered : 0.0;
        const double w = moment ? std::sqrt(ratio) : ratio;
        const float word = w > 0.0 && w < 3e38 ? static_cast<float>(w) : std::numeric_limits<float>::max();
        windowWords_[s] = floatBits(word);
        // the device's shortcut past the first vertex (fen_guide.h window_min): the exact float it compares
        deviceParams_.window_min = windowSlots_ == 0 ? word : std::min(deviceParams_.window_min, word);
        ++windowSlots_;
    }
}

void FirstBounceGuide::upload()
{
    auto& q = ctx_.queue();
    q.enqueueWriteBuffer(params_, CL_FALSE, 0, sizeof deviceParams_, &deviceParams_);
    const auto section = [&](std::uint32_t at, const std::vector<std::uint32_t>& words) {
        if (!words.empty())
            q.enqueueWriteBuffer(tables_, CL_FALSE, std::size_t{at} * 4, words.size() * 4, words.data());
    };
    section(0, records_);
    section(deviceParams_.voxels_at, voxelWord_);
    section(deviceParams_.spatial_at, spatialWords_);
    section(deviceParams_.nodes_at, nodeWords_);
    section(deviceParams_.leaves_at, leafWords_);
    section(deviceParams_.columns_at, columnWords_);
    if (deviceParams_.windows_at) {
        section(deviceParams_.windows_at, windowWords_);
        section(deviceParams_.leaf_slots_at, leafSlotWords_);
    }
    q.finish();
}

// The spatial trees, voxel by voxel, depth first: 1 a node (its lower half, then its upper), or 0
// and the spatial leaf's index. Independent of how the nodes are numbered.
std::vector<std::uint64_t> FirstBounceGuide::spaceShape() const
{
    std::vector<std::uint64_t> space;
    std::function<void(std::uint32_t)> walk = [&](std::uint32_t word) {
        if (word & FEN_GUIDE_LEAF) {
            space.push_back(0);
            space.push_back(word & ~FEN_GUIDE_LEAF);
            return;
        }
        space.push_back(1);
        walk(spatialNodes_[word][0]);
        walk(spatialNodes_[word][1]);
    };
    if (opt_.enabled)
        for (std::uint32_t word : voxelWord_)
            walk(word);
    return space;
}

std::size_t FirstBounceGuide::nodeCount() const
{
    std::size_t n = 0;
    for (const Tree& t : trees_)
        n += t.nodes.size();
    return n;
}

// Halves every spatial leaf with a slot whose table will steer (promising_) and whose slots
// gathered spatialSplitConnections contributions in the pass (per slot as it was read), most first
// while the capacity lasts. Each half starts from its parent's trees with half their totals: the parent's learning is
// the best guess for both until the next pass tells them apart. Returns the splits made.
std::size_t FirstBounceGuide::refineSpace(const std::vector<double>& passConnections)
{
    struct Candidate {
        double connections;
        std::uint32_t leaf;
    };
    std::vector<Candidate> cand;
    for (std::uint32_t l = 0; l < spatialLeaves_.size(); ++l) {
        double c = 0.0;
        for (std::uint32_t k = 0; k < FEN_GUIDE_SIDES; ++k)
            c += passConnections[FEN_GUIDE_SIDES * l + k];
        bool steered = false;  // only where a table steers: elsewhere the split buys nothing
        for (std::uint32_t k = 0; k < FEN_GUIDE_SIDES; ++k)
            steered = steered || promising_[FEN_GUIDE_SIDES * l + k];
        if (steered && c >= opt_.spatialSplitConnections &&
            static_cast<int>(spatialLeaves_[l].depth) < opt_.maxSpatialDepth)
            cand.push_back({c, l});
    }
    std::sort(cand.begin(), cand.end(), [](const Candidate& a, const Candidate& b) {
        return a.connections != b.connections ? a.connections > b.connections : a.leaf < b.leaf;
    });
    std::size_t made = 0, nodes = nodeCount();
    deferredSpatialSplits_ = 0;
    for (const Candidate& c : cand) {
        std::size_t leaves = 0, treeNodes = 0;
        for (std::uint32_t k = 0; k < FEN_GUIDE_SIDES; ++k) {
            leaves += trees_[FEN_GUIDE_SIDES * c.leaf + k].leaves.size();
            treeNodes += trees_[FEN_GUIDE_SIDES * c.leaf + k].nodes.size();
        }
        if (leafCount_ + leaves > leafCapacity_ || nodes + treeNodes > nodeCapacity_ ||
            trees_.size() + FEN_GUIDE_SIDES > slotCapacity_ || spatialNodes_.size() + 1 > spatialCapacity_) {
            ++deferredSpatialSplits_;
            continue;
        }
        const auto node = static_cast<std::uint32_t>(spatialNodes_.size());
        const auto upper = static_cast<std::uint32_t>(spatialLeaves_.size());
        SpatialLeaf& lower = spatialLeaves_[c.leaf];
        if (lower.node < 0)
            voxelWord_[lower.voxel] = node;
        else
            spatialNodes_[static_cast<std::size_t>(lower.node)][lower.half] = node;
        spatialNodes_.push_back({FEN_GUIDE_LEAF | c.leaf, FEN_GUIDE_LEAF | upper});
        lower.node = node;
        lower.half = 0;
        lower.depth += 1;
        SpatialLeaf u = lower;
        u.half = 1;
        spatialLeaves_.push_back(u);
        for (std::uint32_t k = 0; k < FEN_GUIDE_SIDES; ++k) {
            Tree& t = trees_[FEN_GUIDE_SIDES * c.leaf + k];
            for (Leaf& l : t.leaves)
                l.scaleTotals(0.5);
            t.window.scale(0.5);
            trees_.push_back(t);  // the upper half's slot FEN_GUIDE_SIDES upper + k
        }
        leafCount_ += leaves;
        nodes += treeNodes;
        ++made;
    }
    return made;
}

void FirstBounceGuide::learn()
{
    if (!opt_.enabled)
        return;
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<std::uint64_t>& raw = statsRead_;
    raw.resize(leafCount_ * FEN_GUIDE_STATS_WORDS);
    ctx_.queue().enqueueReadBuffer(stats_, CL_TRUE, 0, raw.size() * 8, raw.data());
    std::vector<std::uint64_t>& windowRaw = windowRead_;
    windowRaw.resize(deviceParams_.windows_at ? trees_.size() * FEN_GUIDE_WINDOW_WORDS : 0);
    if (!windowRaw.empty())
        ctx_.queue().enqueueReadBuffer(windowStats_, CL_TRUE, 0, windowRaw.size() * 8, windowRaw.data());
    const double scale = std::ldexp(1.0, -2 * kStatsFixedPointBits);
    PassStats& pass = pass_;
    pass.first.resize(trees_.size() + 1);
    pass.first[0] = 0;
    for (std::size_t s = 0; s < trees_.size(); ++s)
        pass.first[s + 1] = pass.first[s] + trees_[s].leaves.size();
    pass.sumSq.resize(leafCount_);  // every element is written below
    pass.connections.resize(leafCount_);
    std::vector<double> passConnections(trees_.size(), 0.0);
    // Slot by slot, each writing only its own leaves and sums: the slots in shares over the threads.
    inShares(trees_.size(), [&](std::size_t s0, std::size_t s1) {
        for (std::size_t s = s0; s < s1; ++s) {
            Tree& t = trees_[s];
            const std::uint64_t* w = raw.data() + pass.first[s] * FEN_GUIDE_STATS_WORDS;
            for (std::size_t i = 0; i < t.leaves.size(); ++i, w += FEN_GUIDE_STATS_WORDS) {
                Leaf& l = t.leaves[i];
                const std::size_t at = pass.first[s] + i;
                // v^2 d(b), d the density the pass drew the leaf with: an estimate of the leaf's S(b).
                pass.sumSq[at] = fixed128(w + FEN_GUIDE_SUMSQ_LO) * scale * l.density;
                pass.connections[at] = static_cast<double>(w[FEN_GUIDE_CONNECTIONS]);
                l.sumSq += pass.sumSq[at];
                l.connections += pass.connections[at];
                passConnections[s] += pass.connections[at];
            }
            if (!windowRaw.empty()) {
                // the window's sums, at their scale (the squares at its square): rebuildWindows()
                const std::uint64_t* ww = windowRaw.data() + s * FEN_GUIDE_WINDOW_WORDS;
                t.window.delivered += fixed128(ww + FEN_GUIDE_DELIVERED_LO);
                t.window.arrived += fixed128(ww + FEN_GUIDE_ARRIVED_LO);
                t.window.visits += static_cast<double>(ww[FEN_GUIDE_VISITS]);
            }
        }
    }, 64);
    // the aim's sums over every slot, in slot order (deterministic)
    passAimSums_ = AimSums{};
    if (deviceParams_.aim_sums)
        for (std::size_t s = 0; s < trees_.size(); ++s) {
            const std::uint64_t* ww = windowRaw.data() + s * FEN_GUIDE_WINDOW_WORDS;
            passAimSums_.mixed += fixed128(ww + FEN_GUIDE_MIXED_SQ_LO);
            passAimSums_.aimed += fixed128(ww + FEN_GUIDE_AIMED_SQ_LO);
        }
    lastSplits_ = refine(pass);  // keeps leafCount_
    lastSpatialSplits_ = refineSpace(passConnections);
    rebuild();
    upload();
    clearStats();
    lastLearnSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    learnSeconds_ += lastLearnSeconds_;
}

std::vector<FirstBounceGuide::LeafView> FirstBounceGuide::leaves(std::uint32_t slot) const
{
    const Tree& t = trees_.at(slot);
    const std::uint32_t first = records_.at(4 * std::size_t{slot} + 1);
    const double unit = std::ldexp(1.0, -FEN_GUIDE_MAX_DEPTH);
    std::vector<LeafView> v;
    for (std::size_t b = 0; b < t.leaves.size(); ++b) {
        const Leaf& l = t.leaves[b];
        v.push_back({l.x0 * unit, l.y0 * unit, std::ldexp(1.0, -static_cast<int>(l.depth)),
                     l.density * l.area(), first + static_cast<std::uint32_t>(b)});
    }
    return v;
}

// Slots whose tree was refined or has seen light: their shapes (depth first, per child: 1 a node,
// 0 a leaf; the root is always a node), their leaves' (sum, contributions) and their window totals
// (delivered, arrived, visits; zeros without weight windows).
void FirstBounceGuide::save(StateWriter& w) const
{
    std::vector<std::uint64_t> slots, shape;
    std::vector<double> leaves, windows;
    for (std::size_t s = 0; s < trees_.size(); ++s) {
        const Tree& t = trees_[s];
        const bool seen = t.window.visits > 0.0 || std::any_of(t.leaves.begin(), t.leaves.end(), [](const Leaf& l) {
                              return l.sumSq > 0.0 || l.connections > 0.0;
                          });
        if (!seen && isInitial(t))
            continue;
        slots.push_back(s);
        std::function<void(std::int32_t)> walk = [&](std::int32_t n) {
            for (int q = 0; q < 4; ++q) {
                const std::int32_t c = t.nodes[static_cast<std::size_t>(n)][q];
                shape.push_back(c >= 0 ? 1u : 0u);
                if (c >= 0)
                    walk(c);
            }
        };
        walk(0);
        for (const Leaf& l : t.leaves) {
            const auto v = l.totals();
            leaves.insert(leaves.end(), v.begin(), v.end());
        }
        const auto v = t.window.totals();
        windows.insert(windows.end(), v.begin(), v.end());
    }
    w.u64s("guide.space", spaceShape());
    w.u64s("guide.slots", slots);
    w.u64s("guide.shape", shape);
    w.f64s("guide.leaves", leaves);
    w.f64s("guide.windows", windows);
    w.u64s("guide.splits", {lastSplits_, deferredSplits_, lastSpatialSplits_, deferredSpatialSplits_});
}

void FirstBounceGuide::load(StateReader& r)
{
    // The spatial trees first: they say how many slots there are.
    // Written: a word per spatial node, two per spatial leaf; nodes < leaves <= spatialCapacity_.
    const std::vector<std::uint64_t> space = r.u64s("guide.space", 3 * spatialCapacity_ + 2 * voxelWord_.size());
    std::vector<std::uint32_t> voxelWord(voxelWord_.size());
    std::vector<std::array<std::uint32_t, 2>> spatialNodes;
    std::vector<SpatialLeaf> spatialLeaves;
    std::vector<char> seenLeaf;
    std::size_t sp = 0;
    std::function<std::uint32_t(std::uint32_t, std::int64_t, std::uint32_t, std::uint32_t)> parseSpace =
        [&](std::uint32_t voxel, std::int64_t node, std::uint32_t half, std::uint32_t depth) -> std::uint32_t {
        if (sp >= space.size() || space[sp] > 1)
            r.fail("guide.space", "ends early or holds a flag other than 0 and 1");
        if (space[sp++] == 0) {
            if (sp >= space.size() || space[sp] >= spatialCapacity_ || space[sp] >= (1u << 31))
                r.fail("guide.space", "a spatial leaf out of range");
            const auto leaf = static_cast<std::uint32_t>(space[sp++]);
            if (leaf >= seenLeaf.size()) {
                seenLeaf.resize(leaf + 1, 0);
                spatialLeaves.resize(leaf + 1);
            }
            if (seenLeaf[leaf])
                r.fail("guide.space", "a spatial leaf listed twice");
            seenLeaf[leaf] = 1;
            spatialLeaves[leaf] = {voxel, node, half, depth};
            return FEN_GUIDE_LEAF | leaf;
        }
        if (depth >= static_cast<std::uint32_t>(opt_.maxSpatialDepth) || spatialNodes.size() >= spatialCapacity_)
            r.fail("guide.space", "a spatial tree deeper or larger than the guide allows");
        const auto at = static_cast<std::uint32_t>(spatialNodes.size());
        spatialNodes.push_back({});
        const std::uint32_t lower = parseSpace(voxel, at, 0, depth + 1);
        spatialNodes[at][0] = lower;
        const std::uint32_t upper = parseSpace(voxel, at, 1, depth + 1);
        spatialNodes[at][1] = upper;
        return at;
    };
    for (std::uint32_t v = 0; v < voxelWord.size(); ++v)
        voxelWord[v] = parseSpace(v, -1, 0, 0);
    if (sp != space.size() || std::find(seenLeaf.begin(), seenLeaf.end(), 0) != seenLeaf.end() ||
        FEN_GUIDE_SIDES * seenLeaf.size() > slotCapacity_)
        r.fail("guide.space", "values left over, a spatial leaf missing, or more slots than the memory holds");
    const std::vector<std::uint64_t> slots = r.u64s("guide.slots", FEN_GUIDE_SIDES * seenLeaf.size());
    const std::vector<std::uint64_t> shape = r.u64s("guide.shape", 4 * nodeCapacity_);
    const std::vector<double> leaves = r.f64s("guide.leaves", kSavedPerLeaf * leafCapacity_);
    const std::vector<double> windows = r.f64s("guide.windows", kSavedPerWindow * slots.size(), true);
    const std::vector<std::uint64_t> splits = r.u64s("guide.splits", 4);
    if (splits.size() != 4)
        r.fail("guide.splits", "not (last, deferred, spatial, spatial deferred)");
    std::vector<Tree> trees(FEN_GUIDE_SIDES * seenLeaf.size(), initialTree());
    std::size_t at = 0, leafAt = 0, total = 0;
    for (std::size_t k = 0; k < slots.size(); ++k) {
        if (slots[k] >= trees.size() || (k > 0 && slots[k] <= slots[k - 1]))
            r.fail("guide.slots", "a slot out of range or out of order");
        Tree t;
        std::function<void(std::uint32_t, std::uint32_t, std::uint32_t)> parse = [&](std::uint32_t x0,
                                                                                     std::uint32_t y0,
                                                                                     std::uint32_t depth) {
            const auto n = t.nodes.size();
            t.nodes.push_back({});
            for (std::uint32_t q = 0; q < 4; ++q) {
                if (at >= shape.size() || shape[at] > 1)
                    r.fail("guide.shape", "ends early or holds a value other than 0 and 1");
                Leaf l = quadrant(x0, y0, depth, q);
                if (shape[at++] == 1) {
                    if (l.depth >= FEN_GUIDE_MAX_DEPTH)
                        r.fail("guide.shape", "a tree deeper than the guide allows");
                    t.nodes[n][q] = static_cast<std::int32_t>(t.nodes.size());
                    parse(l.x0, l.y0, l.depth);
                } else {
                    if (leafAt + kSavedPerLeaf > leaves.size())
                        r.fail("guide.leaves", "fewer leaves than the trees' shapes hold");
                    static_assert(std::tuple_size<decltype(l.totals())>::value == kSavedPerLeaf);
                    for (double* v : l.totals()) {
                        *v = r.finite("guide.leaves", leaves[leafAt++]);
                        if (*v < 0.0)
                            r.fail("guide.leaves", "a negative sum or count");
                    }
                    t.nodes[n][q] = ~static_cast<std::int32_t>(t.leaves.size());
                    t.leaves.push_back(l);
                }
            }
        };
        parse(0, 0, 0);
        static_assert(std::tuple_size<decltype(t.window.totals())>::value == kSavedPerWindow);
        std::size_t windowAt = kSavedPerWindow * k;
        for (double* v : t.window.totals()) {
            *v = r.finite("guide.windows", windows[windowAt++]);
            if (*v < 0.0)
                r.fail("guide.windows", "a negative sum or count");
        }
        trees[slots[k]] = std::move(t);
    }
    if (at != shape.size() || leafAt != leaves.size())
        r.fail("guide.shape", "values left over after the listed slots' trees");
    std::size_t nodes = 0;
    for (const Tree& t : trees) {
        total += t.leaves.size();
        nodes += t.nodes.size();
    }
    if (total > leafCapacity_ || nodes > nodeCapacity_)
        r.fail("guide.shape", "more leaves than --adaptive-guide-memory holds");
    trees_ = std::move(trees);
    voxelWord_ = std::move(voxelWord);
    spatialNodes_ = std::move(spatialNodes);
    spatialLeaves_ = std::move(spatialLeaves);
    lastSplits_ = splits[0];
    deferredSplits_ = splits[1];
    lastSpatialSplits_ = splits[2];
    deferredSpatialSplits_ = splits[3];
    rebuild();
    upload();
    clearStats();
}

nlohmann::json FirstBounceGuide::report() const
{
    if (!opt_.enabled)
        return {{"enabled", false}};
    // The checksum covers the spatial trees' shape and every direction tree's shape and totals: equal checksums, equal guides (the
    // determinism tests compare them).
    double connections = 0.0;
    Fnv checksum;
    for (std::uint64_t v : spaceShape())
        checksum.value(v);
    for (const Tree& t : trees_) {
        for (const Leaf& l : t.leaves) {
            connections += l.connections;
            checksum.value(l.sumSq);
            checksum.value(l.connections);
            checksum.value(l.depth);
        }
        if (opt_.window)
            for (double v : t.window.totals())  // the fused kernel holds arrivals a while: the sums must agree too
                checksum.value(v);
        checksum.value(t.learned);
    }
    const double used = trees_.size() * 16.0 + leafCount_ * kBytesPerLeaf + 4.0 * voxelWord_.size() +
                        (deviceParams_.windows_at ? leafCount_ * 4.0 + trees_.size() * kWindowBytesPerSlot : 0.0) +
                        8.0 * spatialNodes_.size();
    std::uint32_t maxSpatial = 0;
    for (const SpatialLeaf& l : spatialLeaves_)
        maxSpatial = std::max(maxSpatial, l.depth);
    return {{"enabled", true},
            {"slots", trees_.size()},
            {"voxel_m", side_m_ / cells_},
            {"spatial_leaves", spatialLeaves_.size()},
            {"max_spatial_depth", maxSpatial},
            {"spatial_splits_last_pass", lastSpatialSplits_},
            {"spatial_splits_deferred", deferredSpatialSplits_},
            {"share", opt_.share},
            {"min_connections", opt_.minConnections},
            {"min_gain", opt_.minGain},
            {"max_depth", opt_.maxDepth},
            {"split_share", opt_.splitShare},
            {"space_split", opt_.spatialSplitConnections},
            {"candidate_slots", candidateSlots_},
            {"learned_slots", learnedSlots_},
            {"leaves", leafCount_},
            {"leaf_capacity", leafCapacity_},
            {"max_leaf_depth", maxDepthSeen_},
            {"splits_last_pass", lastSplits_},
            {"splits_deferred", deferredSplits_},
            {"connections", connections},
            {"checksum", checksum.h},
            {"window", opt_.window ? (opt_.windowRule == GuideOptions::WindowRule::Moment ? "moment" : "mean") : "off"},
            {"window_slots", windowSlots_},
            {"window_target", windowTarget_},
            {"window_split_max", opt_.windowSplitMax},
            {"window_min_survival", opt_.windowMinSurvival},
            {"window_vertices", opt_.windowEveryVertex ? "every" : "first"},
            {"window_later", opt_.windowEveryVertex ? opt_.windowLater : 0.0},
            {"learn_seconds", learnSeconds_},
            {"learn_seconds_last_pass", lastLearnSeconds_},
            {"memory_bytes", deviceBytes_},
            {"memory_used_bytes", static_cast<std::uint64_t>(used)}};
}

}  // namespace fen
