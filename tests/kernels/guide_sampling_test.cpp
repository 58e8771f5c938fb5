// guide_sampling_test.cpp — the first-bounce guide (DESIGN.md §3.4) against the density it claims:
// from statistics the test writes, learn() builds each slot's table as the documented mixture
// (1 - share) sqrt(S(b) A(b)) / sum + share A(b) -- exactly, up to the integer table's 2^-32
// units -- and leaves uniform a slot with too few contributions and one whose table would not cut
// the second moment minGain times; it refines a slot's quadtree one level per pass where the
// density concentrates, within the memory cap, largest shares first; the device then draws leaves
// with exactly the realised probabilities (chi-square, p > 1e-3, fixed seed), each point inside
// its leaf, with the density d(b) = P(b) / A(b) that the path's weight is divided by, and its
// descent finds the host's leaf for any point; the checkpoint carries the trees; the weight windows
// are the target over each slot's adjoint, from the sums the test writes. Unbiasedness of the whole render
// with the guide on: Analytic.GuidedFirstBounceConservesEnergy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>

#include "cl/launch.h"
#include "io/state_io.h"
#include "util/error.h"
#include "scatter/first_bounce_guide.h"
#include "shared/fen_openings.h"
#include "shared/fen_render.h"
#include "support/cl_fixture.h"
#include "support/statistics.h"

namespace fen {
namespace {

GuideOptions options()
{
    GuideOptions o;
    o.enabled = true;
    o.share = 0.25;
    o.minConnections = 32.0;
    o.minGain = 2.0;  // the gate under test (the default, 1, steers every slot that has seen enough)
    return o;
}

// Writes the statistics a pass would leave for one slot's leaves whose integrals of the squared
// delivery are S(b) = r(b)^2: the sum of v^2 over the leaf's samples estimates S(b) / d(b), d the
// density the slot's table draws the leaf with (1 where it is the cosine's); r in units of the
// device's v (scaled by 2^20, squared: 2^40); and a count per leaf.
void writeSlot(ocl::Context& ctx, const FirstBounceGuide& g, std::uint32_t slot, const std::vector<double>& r,
               std::uint64_t countPerLeaf)
{
    const auto leaves = g.leaves(slot);
    ASSERT_EQ(leaves.size(), r.size());
    std::vector<std::uint64_t> words(leaves.size() * FEN_GUIDE_STATS_WORDS, 0);
    for (std::size_t b = 0; b < leaves.size(); ++b) {
        const double d = leaves[b].probability / (leaves[b].size * leaves[b].size);
        words[FEN_GUIDE_STATS_WORDS * b + FEN_GUIDE_SUMSQ_LO] = static_cast<std::uint64_t>(std::ldexp(r[b] * r[b] / d, 40));
        words[FEN_GUIDE_STATS_WORDS * b + FEN_GUIDE_CONNECTIONS] = countPerLeaf;
    }
    // A slot's leaves have consecutive global indices.
    ctx.queue().enqueueWriteBuffer(g.stats(), CL_TRUE, std::size_t{leaves[0].index} * FEN_GUIDE_STATS_WORDS * 8,
                                   words.size() * 8, words.data());
}

// n device draws from learned slot `slot`: (u1, u2, d, global leaf).
std::vector<cl_float4> draw(ocl::Context& ctx, const FirstBounceGuide& g, std::uint32_t slot, std::uint32_t n)
{
    cl::Kernel k(ctx.program("test_guide_probes.cl"), "guide_sample_probe");
    cl::Buffer out = ctx.buffer(CL_MEM_WRITE_ONLY, std::size_t{n} * 16, "probe output");
    ocl::setKernelArgs(k, g.params(), g.tables(), slot, std::uint32_t{17}, n, out);
    ocl::launch(ctx, k, "guide_sample_probe", n);
    std::vector<cl_float4> v(n);
    ctx.queue().enqueueReadBuffer(out, CL_TRUE, 0, std::size_t{n} * 16, v.data());
    return v;
}

// Draws match the realised table (chi-square), each point lies in its leaf, and the density the
// weight is divided by is P(b) / A(b).
void expectDrawsFollowTheTable(ocl::Context& ctx, const FirstBounceGuide& g, std::uint32_t slot)
{
    const auto leaves = g.leaves(slot);
    const std::uint32_t n = 1u << 20;
    const std::vector<cl_float4> v = draw(ctx, g, slot, n);
    std::vector<double> observed(leaves.size(), 0.0), expected(leaves.size());
    int outside = 0, wrongDensity = 0;
    for (const cl_float4& s : v) {
        std::uint32_t key;
        std::memcpy(&key, &s.s[3], 4);
        ASSERT_GE(key, leaves[0].index);
        ASSERT_LT(key - leaves[0].index, leaves.size());
        const auto& l = leaves[key - leaves[0].index];
        observed[key - leaves[0].index] += 1.0;
        outside += !(s.s[0] >= l.x0 && s.s[0] < l.x0 + l.size && s.s[1] >= l.y0 && s.s[1] < l.y0 + l.size);
        wrongDensity += s.s[2] != static_cast<float>(l.probability / (l.size * l.size));
    }
    for (std::size_t b = 0; b < leaves.size(); ++b)
        expected[b] = n * leaves[b].probability;
    const double pv = test::chiSquarePValue(observed, expected);
    std::printf("[ guide ] slot %u: %zu leaves drawn against the realised table: chi-square p = %.3g\n", slot,
                leaves.size(), pv);
    EXPECT_GT(pv, 1e-3);
    EXPECT_EQ(outside, 0) << "points outside the leaf drawn";
    EXPECT_EQ(wrongDensity, 0) << "densities other than P(b) / A(b)";
}

// The device's descent (guide_leaf) finds, for points of the square, the leaf the host's tree holds
// them in.
void expectDescentFindsTheLeaves(ocl::Context& ctx, const FirstBounceGuide& g, std::uint32_t slot)
{
    const auto leaves = g.leaves(slot);
    std::vector<cl_float2> sq;
    std::vector<std::uint32_t> want;
    for (const auto& l : leaves)
        for (double fx : {0.0, 0.37, 0.999})
            for (double fy : {0.0, 0.61, 0.999}) {
                sq.push_back({{static_cast<float>(l.x0 + fx * l.size), static_cast<float>(l.y0 + fy * l.size)}});
                want.push_back(l.index);
            }
    const auto count = static_cast<std::uint32_t>(sq.size());
    cl::Buffer in = ctx.buffer(CL_MEM_READ_ONLY, sq.size() * 8, "points", sq.data());
    cl::Buffer out = ctx.buffer(CL_MEM_WRITE_ONLY, sq.size() * 4, "leaves");
    cl::Kernel k(ctx.program("test_guide_probes.cl"), "guide_leaf_probe");
    ocl::setKernelArgs(k, g.params(), g.tables(), slot, in, count, out);
    ocl::launch(ctx, k, "guide_leaf_probe", count);
    std::vector<std::uint32_t> got(sq.size());
    ctx.queue().enqueueReadBuffer(out, CL_TRUE, 0, got.size() * 4, got.data());
    EXPECT_EQ(got, want);
}

// A guide with options o loaded from g's checkpoint state, as a resumed render builds it.
std::unique_ptr<FirstBounceGuide> resumed(ocl::Context& ctx, const GuideOptions& o, const FirstBounceGuide& g)
{
    StateWriter w;
    g.save(w);
    auto h = std::make_unique<FirstBounceGuide>(ctx, o, glm::dvec3(0.0), 8.0);
    StateReader rd(w.bytes(), "test.ckpt");
    h->load(rd);
    rd.end();
    return h;
}

TEST(GuideSampling, LearnedTableIsTheDocumentedMixtureAndTheDeviceDrawsIt)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    FirstBounceGuide g(*ctx, options(), glm::dvec3(0.0), 8.0);
    // Slot 5: two leaves carry nearly everything (the table predicts a 24x cut); slot 6: the same,
    // but no contributions counted yet; slot 7: a gentle ramp, a cut far below minGain = 2.
    // One contribution per leaf: too few for a split, so the trees keep their 8 x 8 leaves.
    std::vector<double> r(64, 1.0), ramp(64);
    r[9] = 400.0;
    r[10] = 200.0;
    double total = 0.0;
    for (int b = 0; b < 64; ++b) {
        total += r[b];
        ramp[b] = 1.0 + 0.02 * b;
    }
    writeSlot(*ctx, g, 5, r, 1);     // 64 contributions: learned
    writeSlot(*ctx, g, 6, r, 0);     // none: stays the cosine
    writeSlot(*ctx, g, 7, ramp, 1);  // enough seen, too little to gain: stays the cosine
    g.learn();
    EXPECT_EQ(g.learnedSlots(), 1u);
    EXPECT_TRUE(g.learned(5));
    const auto leaves = g.leaves(5);
    ASSERT_EQ(leaves.size(), 64u);
    for (int b = 0; b < 64; ++b) {
        // Equal areas 1/64: m(b) = sqrt(S(b) / 64) is r(b) / 8, the mixture as documented.
        EXPECT_NEAR(leaves[b].probability, 0.75 * r[b] / total + 0.25 / 64.0, 1e-8) << "leaf " << b;
        for (std::uint32_t slot : {6u, 7u})
            EXPECT_EQ(g.leaves(slot)[b].probability, 1.0 / 64.0) << "slot " << slot << ", leaf " << b;
    }
    // The statistics were cleared and the totals kept: another pass with nothing new changes nothing.
    g.learn();
    const auto again = g.leaves(5);
    for (int b = 0; b < 64; ++b)
        EXPECT_EQ(again[b].probability, leaves[b].probability);
    expectDrawsFollowTheTable(*ctx, g, 5);
}

// Writes the weight-window sums (fen_guide.h) of a slot as the device sums them for the rule's
// power: delivered and arrived (whole fixed-point units) to that power, and visits (so that per slot
// the moment rule's ratio is the square of the mean rule's).
void writeWindowSums(ocl::Context& ctx, const FirstBounceGuide& g, GuideOptions::WindowRule rule, std::uint32_t slot,
                     std::uint64_t delivered, std::uint64_t arrived, std::uint64_t visits)
{
    const bool squared = rule == GuideOptions::WindowRule::Moment;
    std::vector<std::uint64_t> words(FEN_GUIDE_WINDOW_WORDS, 0);
    words[FEN_GUIDE_DELIVERED_LO] = squared ? delivered * delivered : delivered;
    words[FEN_GUIDE_ARRIVED_LO] = squared ? arrived * arrived : arrived;
    words[FEN_GUIDE_VISITS] = visits;
    ctx.queue().enqueueWriteBuffer(g.windowStats(), CL_TRUE, std::size_t{slot} * FEN_GUIDE_WINDOW_WORDS * 8,
                                   words.size() * 8, words.data());
}

// The windows from the sums writeWindowSums() leaves, per rule; returns the first six slots'.
std::vector<float> windowsOf(ocl::Context& ctx, GuideOptions::WindowRule rule, nlohmann::json* report)
{
    GuideOptions o = options();
    o.window = true;
    o.windowRule = rule;
    o.windowMinVisits = 100.0;
    FirstBounceGuide g(ctx, o, glm::dvec3(0.0), 8.0);
    // Slot 1 delivers 3 per unit of arriving weight, slot 2 a quarter; slot 3 was seen too few
    // times for a window; slot 4 often, and never delivered.
    writeWindowSums(ctx, g, rule, 1, 3000, 1000, 1000);
    writeWindowSums(ctx, g, rule, 2, 1000, 4000, 1000);
    writeWindowSums(ctx, g, rule, 3, 50, 10, 99);
    writeWindowSums(ctx, g, rule, 4, 0, 500, 1000);
    g.learn();
    *report = g.report();
    dev::GuideParams p;
    ctx.queue().enqueueReadBuffer(g.params(), CL_TRUE, 0, sizeof p, &p);
    EXPECT_GT(p.windows_at, 0u);
    EXPECT_EQ(p.window_split_max, 16u);
    EXPECT_EQ(p.window_power, rule == GuideOptions::WindowRule::Moment ? 2u : 1u);
    // Every leaf's word names the slot whose tree holds it: a connection finds its path's window
    // statistics by it (lib/guide.h guide_window_word).
    for (std::uint32_t slot : {0u, 1u, 5u, static_cast<std::uint32_t>(g.slotCount() - 1)}) {
        for (const auto& leaf : g.leaves(slot)) {
            std::uint32_t word = 0;
            ctx.queue().enqueueReadBuffer(g.tables(), CL_TRUE, (std::size_t{p.leaf_slots_at} + leaf.index) * 4, 4,
                                          &word);
            EXPECT_EQ(word, slot) << "leaf " << leaf.index;
        }
    }
    std::vector<float> w(6);
    ctx.queue().enqueueReadBuffer(g.tables(), CL_TRUE, std::size_t{p.windows_at} * 4, w.size() * 4, w.data());
    // The smallest window, the device's bound past the first vertex (a path under twice it splits
    // nowhere): slots 1 and 2 have windows, slot 4 the largest float, slot 3 and the rest none.
    EXPECT_EQ(p.window_min, std::min(w[1], w[2]));
    EXPECT_GT(p.window_min, 0.0f);
    // The totals survive a checkpoint: the reloaded guide makes the same windows.
    StateWriter out;
    g.save(out);
    FirstBounceGuide h(ctx, o, glm::dvec3(0.0), 8.0);
    StateReader in(out.bytes(), "test state");
    h.load(in);
    EXPECT_EQ(h.report()["window_target"], (*report)["window_target"]);
    std::vector<float> v(6);
    ctx.queue().enqueueReadBuffer(h.tables(), CL_TRUE, std::size_t{p.windows_at} * 4, v.size() * 4, v.data());
    EXPECT_EQ(v, w);
    // The totals belong to the slot, not to its leaves: when slot 1's tree refines (a bright leaf),
    // its window and the target stay.
    std::vector<double> r(64, 0.5);
    r[9] = 1e3;
    writeSlot(ctx, h, 1, r, 100);
    h.learn();
    EXPECT_GT(h.leaves(1).size(), 64u) << "slot 1 refined";
    EXPECT_EQ(h.report()["window_target"], (*report)["window_target"]);
    ctx.queue().enqueueReadBuffer(h.tables(), CL_TRUE, std::size_t{p.windows_at} * 4, v.size() * 4, v.data());
    EXPECT_EQ(v, w);
    return w;
}

TEST(GuideSampling, WindowsAreTheTargetOverTheAdjoint)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // The windows are in the units of the sums, which the device compares its own with.
    const double unit = 1.0;
    nlohmann::json report;
    // Mean: T = all delivered / all visits, w = T / J with J = delivered / arrived.
    const std::vector<float> w = windowsOf(*ctx, GuideOptions::WindowRule::Mean, &report);
    const double target = (3000.0 + 1000.0 + 50.0) / (1000.0 + 1000.0 + 99.0 + 1000.0);
    EXPECT_DOUBLE_EQ(report["window_target"].get<double>(), target);
    EXPECT_EQ(report["window_slots"].get<int>(), 3);
    EXPECT_EQ(w[0], 0.0f);  // never seen
    EXPECT_FLOAT_EQ(w[1], static_cast<float>(target / 3.0 * unit));
    EXPECT_FLOAT_EQ(w[2], static_cast<float>(target * 4.0 * unit));
    EXPECT_EQ(w[3], 0.0f);
    EXPECT_EQ(w[4], std::numeric_limits<float>::max());
    // Moment: tau^2 = all delivered^2 / all visits, w = tau / sqrt(M) with M = delivered^2 / arrived^2.
    const std::vector<float> m = windowsOf(*ctx, GuideOptions::WindowRule::Moment, &report);
    const double tau2 = (9e6 + 1e6 + 2500.0) / (1000.0 + 1000.0 + 99.0 + 1000.0);
    EXPECT_DOUBLE_EQ(report["window_target"].get<double>(), tau2);
    EXPECT_EQ(report["window"], "moment");
    EXPECT_EQ(m[0], 0.0f);
    EXPECT_FLOAT_EQ(m[1], static_cast<float>(std::sqrt(tau2) / 3.0 * unit));
    EXPECT_FLOAT_EQ(m[2], static_cast<float>(std::sqrt(tau2) * 4.0 * unit));
    EXPECT_EQ(m[3], 0.0f);
    EXPECT_EQ(m[4], std::numeric_limits<float>::max());
}

// The fused kernel holds each work-item's window arrivals in registers (lib/guide.h HeldArrivals)
// and adds them to memory when another slot takes their entry or the work-item ends; the wavefront
// adds each at once. Both must leave exactly the sums of the values (to the rule's power, carries
// into the high word included, modulo nothing: none reaches 2^128), the visits, and the same count
// of values dropped as beyond 2^127.
TEST(GuideSampling, HeldArrivalsLeaveTheSumsOfAddingEachAtOnce)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    GuideOptions o = options();
    o.window = true;
    o.windowRule = GuideOptions::WindowRule::Moment;
    FirstBounceGuide g(*ctx, o, glm::dvec3(0.0), 8.0);
    dev::GuideParams p;
    ctx->queue().enqueueReadBuffer(g.params(), CL_TRUE, 0, sizeof p, &p);
    ASSERT_EQ(p.window_power, 2u) << "the moment rule sums squares";
    constexpr std::uint32_t items = 256, per = 64, slots = 24;
    std::mt19937 rng(7);
    std::vector<std::uint32_t> slot(items * per);
    std::vector<float> a(items * per);
    std::vector<unsigned __int128> sum(slots, 0);
    std::vector<std::uint64_t> visits(slots, 0);
    std::uint64_t overflows = 0;
    for (std::size_t i = 0; i < slot.size(); ++i) {
        // half in one slot (runs), the rest over 24 (evictions: 8 entries, slots 3, 11, 19 share one)
        slot[i] = rng() % 2 ? 3u : static_cast<std::uint32_t>(rng() % slots);
        // a = k 2^e: its square k^2 2^2e is exact in float (k^2 < 2^24); 2^60 and more need the
        // high word, and most of e = 62 (and some of 57) reach 2^127 and are dropped
        const std::uint32_t k = 1 + static_cast<std::uint32_t>(rng() % 4095);
        const int e = std::array<int, 6>{0, 10, 30, 50, 57, 62}[rng() % 6];
        a[i] = std::ldexp(static_cast<float>(k), e);
        if (std::ldexp(static_cast<double>(k) * k, 2 * e) >= std::ldexp(1.0, 127)) {
            ++overflows;
            continue;
        }
        sum[slot[i]] += static_cast<unsigned __int128>(std::uint64_t{k} * k) << (2 * e);
        ++visits[slot[i]];
    }
    ASSERT_GT(overflows, 0u);
    ASSERT_GT(static_cast<std::uint64_t>(sum[3] >> 64), 0u) << "no carry into the high word";
    cl::Buffer sb = ctx->buffer(CL_MEM_READ_ONLY, slot.size() * 4, "slots", slot.data());
    cl::Buffer ab = ctx->buffer(CL_MEM_READ_ONLY, a.size() * 4, "values", a.data());
    for (std::uint32_t hold : {0u, 1u}) {
        std::vector<std::uint64_t> words(std::size_t{slots} * FEN_GUIDE_WINDOW_WORDS, 0), counters(FEN_CTR_COUNT, 0);
        cl::Buffer wb = ctx->buffer(CL_MEM_READ_WRITE, words.size() * 8, "window sums", words.data());
        cl::Buffer cb = ctx->buffer(CL_MEM_READ_WRITE, counters.size() * 8, "counters", counters.data());
        cl::Kernel k(ctx->program("test_guide_probes.cl"), "guide_arrive_probe");
        ocl::setKernelArgs(k, g.params(), wb, sb, ab, per, items, hold, cb);
        ocl::launch(*ctx, k, "guide_arrive_probe", items);
        ctx->queue().enqueueReadBuffer(wb, CL_TRUE, 0, words.size() * 8, words.data());
        ctx->queue().enqueueReadBuffer(cb, CL_TRUE, 0, counters.size() * 8, counters.data());
        for (std::uint32_t s = 0; s < slots; ++s) {
            const std::uint64_t* w = words.data() + std::size_t{s} * FEN_GUIDE_WINDOW_WORDS;
            EXPECT_EQ(w[FEN_GUIDE_ARRIVED_LO], static_cast<std::uint64_t>(sum[s])) << "hold " << hold << ", slot " << s;
            EXPECT_EQ(w[FEN_GUIDE_ARRIVED_HI], static_cast<std::uint64_t>(sum[s] >> 64))
                << "hold " << hold << ", slot " << s;
            EXPECT_EQ(w[FEN_GUIDE_VISITS], visits[s]) << "hold " << hold << ", slot " << s;
            EXPECT_EQ(w[FEN_GUIDE_DELIVERED_LO], 0u);
        }
        EXPECT_EQ(counters[FEN_CTR_STATS_OVERFLOWS], overflows) << "hold " << hold;
    }
}

// The opening aim's share statistics (fen_guide.h FEN_GUIDE_MIXED_SQ_LO): a contribution's square
// adds to its first vertex's slot's mixed sum only where that vertex drew from the aim's mixture,
// and to the aimed sum only where it drew a direction in the aim's region; never without the
// slot's aim flag, whatever opening the path entered by.
TEST(GuideSampling, ASlotsAimSumsAreOfPathsThatLeftItByTheMixtureAndInTheAimsRegion)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const std::uint32_t worth = FEN_GUIDE_WINDOW_AIM, squared = FEN_GUIDE_WINDOW_SQUARED,
                        mixed = FEN_OPENING_CONNECTION_MIXED, region = FEN_OPENING_CONNECTION_AIM_REGION;
    // slot 2 (plain window sums): left in the aim's region, entered opening side 1 (5); by the
    // mixture's cosine side, entered side 3 (7); by the mixture, through glass that is no learned
    // opening (11); not by the mixture (13: nothing to aim at from there); slot 3 without the flag
    // (17); slot 4 summing squares for the windows (3, the aim's region)
    const std::vector<std::uint32_t> window = {2 | worth, 2 | worth, 2 | worth, 2 | worth, 3, 4 | worth | squared};
    const std::vector<std::uint32_t> opening = {1 | mixed | region, 3 | mixed, FEN_PATH_OPENING_OTHER | mixed, 1,
                                                1 | mixed | region, 2 | mixed | region};
    const std::vector<float> y = {5, 7, 11, 13, 17, 3};
    const std::vector<std::uint32_t> key(y.size(), 0u);
    const auto n = static_cast<std::uint32_t>(y.size());
    std::vector<std::uint64_t> words(5 * FEN_GUIDE_WINDOW_WORDS, 0), stats(FEN_GUIDE_STATS_WORDS, 0),
        counters(FEN_CTR_COUNT, 0);
    cl::Buffer wb = ctx->buffer(CL_MEM_READ_WRITE, words.size() * 8, "window sums", words.data());
    cl::Buffer sb = ctx->buffer(CL_MEM_READ_WRITE, stats.size() * 8, "leaf sums", stats.data());
    cl::Buffer cb = ctx->buffer(CL_MEM_READ_WRITE, counters.size() * 8, "counters", counters.data());
    cl::Buffer kb = ctx->buffer(CL_MEM_READ_ONLY, n * 4, "keys", key.data());
    cl::Buffer yb = ctx->buffer(CL_MEM_READ_ONLY, n * 4, "values", y.data());
    cl::Buffer ob = ctx->buffer(CL_MEM_READ_ONLY, n * 4, "openings", opening.data());
    cl::Buffer vb = ctx->buffer(CL_MEM_READ_ONLY, n * 4, "windows", window.data());
    cl::Kernel k(ctx->program("test_guide_probes.cl"), "guide_record_probe");
    ocl::setKernelArgs(k, sb, wb, kb, yb, vb, ob, 1.0f, n, cb);
    ocl::launch(*ctx, k, "guide_record_probe", n);
    ctx->queue().enqueueReadBuffer(wb, CL_TRUE, 0, words.size() * 8, words.data());
    ctx->queue().enqueueReadBuffer(cb, CL_TRUE, 0, counters.size() * 8, counters.data());
    const auto at = [&](std::uint32_t slot, int word) { return words[std::size_t{slot} * FEN_GUIDE_WINDOW_WORDS + word]; };
    EXPECT_EQ(at(2, FEN_GUIDE_DELIVERED_LO), 36u);             // every contribution, for the windows
    EXPECT_EQ(at(2, FEN_GUIDE_MIXED_SQ_LO), 25u + 49u + 121u); // by the mixture, squared
    EXPECT_EQ(at(2, FEN_GUIDE_AIMED_SQ_LO), 25u);              // ... in the aim's region
    EXPECT_EQ(at(3, FEN_GUIDE_DELIVERED_LO), 17u);
    EXPECT_EQ(at(3, FEN_GUIDE_MIXED_SQ_LO), 0u);
    EXPECT_EQ(at(3, FEN_GUIDE_AIMED_SQ_LO), 0u);
    EXPECT_EQ(at(4, FEN_GUIDE_DELIVERED_LO), 9u);
    EXPECT_EQ(at(4, FEN_GUIDE_MIXED_SQ_LO), 9u);
    EXPECT_EQ(at(4, FEN_GUIDE_AIMED_SQ_LO), 9u);
    EXPECT_EQ(counters[FEN_CTR_STATS_OVERFLOWS], 0u);
}

// learn() reads the aim's share statistics of every slot into one pair for the pass (and none
// without aimSums).
TEST(GuideSampling, APassesAimSumsAreEverySlotsTogether)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    GuideOptions o = options();
    o.window = true;
    o.aimSums = true;
    FirstBounceGuide g(*ctx, o, glm::dvec3(0.0), 8.0);
    const auto write = [&](std::uint32_t slot, std::uint64_t mixed, std::uint64_t aimed) {
        std::vector<std::uint64_t> words(FEN_GUIDE_WINDOW_WORDS, 0);
        words[FEN_GUIDE_MIXED_SQ_LO] = mixed;
        words[FEN_GUIDE_AIMED_SQ_LO] = aimed;
        ctx->queue().enqueueWriteBuffer(g.windowStats(), CL_TRUE, std::size_t{slot} * FEN_GUIDE_WINDOW_WORDS * 8,
                                        words.size() * 8, words.data());
    };
    write(1, 1000, 600);
    write(5, 300, 0);
    g.learn();
    EXPECT_EQ(g.passAimSums().mixed, 1300.0);
    EXPECT_EQ(g.passAimSums().aimed, 600.0);
    g.learn();  // the sums were cleared after the first pass
    EXPECT_EQ(g.passAimSums().mixed, 0.0);
    dev::GuideParams p;
    ctx->queue().enqueueReadBuffer(g.params(), CL_TRUE, 0, sizeof p, &p);
    EXPECT_EQ(p.aim_sums, 1u);
    o.aimSums = false;
    FirstBounceGuide h(*ctx, o, glm::dvec3(0.0), 8.0);
    ctx->queue().enqueueReadBuffer(h.params(), CL_TRUE, 0, sizeof p, &p);
    EXPECT_EQ(p.aim_sums, 0u);
}

TEST(GuideSampling, TreesRefineWhereTheDensityConcentratesAndTheDeviceFollows)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    FirstBounceGuide g(*ctx, options(), glm::dvec3(0.0), 8.0);
    // A bright target near (0.30, 0.71) of the square smaller than any leaf, as a window far away:
    // the leaf holding it has the same S = K whatever its size, so its m = sqrt(K A) keeps more
    // than splitShare of the slot's (the background's 63 eighths hold about 4 against its 2 at
    // depth 9, 1000 / 512). Each pass it must split once, with enough contributions, and nothing else.
    const double tx = 0.30, ty = 0.71;
    std::uint32_t deepest = 0;
    for (int pass = 0; pass < 6; ++pass) {
        const auto leaves = g.leaves(3);
        std::vector<double> r(leaves.size(), 0.5);
        for (std::size_t b = 0; b < leaves.size(); ++b) {
            const auto& l = leaves[b];
            if (tx >= l.x0 && tx < l.x0 + l.size && ty >= l.y0 && ty < l.y0 + l.size)
                r[b] = 1e3;
        }
        writeSlot(*ctx, g, 3, r, 20);
        g.learn();
        const auto now = g.leaves(3);
        EXPECT_EQ(now.size(), 64u + 3u * (pass + 1)) << "pass " << pass << ": one split per pass";
        for (const auto& l : now)
            if (tx >= l.x0 && tx < l.x0 + l.size && ty >= l.y0 && ty < l.y0 + l.size)
                deepest = static_cast<std::uint32_t>(std::lround(-std::log2(l.size)));
    }
    EXPECT_EQ(deepest, 3u + 6u) << "the target's leaf, six levels below the initial eighth";
    EXPECT_TRUE(g.learned(3));
    expectDescentFindsTheLeaves(*ctx, g, 3);
    expectDescentFindsTheLeaves(*ctx, g, 4);  // an untouched slot: the initial 8 x 8
    expectDrawsFollowTheTable(*ctx, g, 3);
    const auto report = g.report();
    EXPECT_EQ(report["max_leaf_depth"], 9u);
    EXPECT_EQ(report["splits_last_pass"], 1u);

    // The checkpoint carries the trees: a guide loaded from it draws with the same tables.
    const auto h = resumed(*ctx, options(), g);
    const auto a = g.leaves(3), b = h->leaves(3);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].probability, b[i].probability);
        EXPECT_EQ(a[i].size, b[i].size);
        EXPECT_EQ(a[i].index, b[i].index);
    }
}

TEST(GuideSampling, TheMemoryCapHoldsAndTheLargestSharesSplitFirst)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    GuideOptions o = options();
    o.voxelsAcross = 1;  // a 2 x 2 x 2 lattice: 48 slots of 64 leaves to start with
    o.splitShare = 4e-6;
    o.memoryMiB = 0.36;  // room for about 7,000 leaves
    FirstBounceGuide g(*ctx, o, glm::dvec3(0.0), 8.0);
    const std::size_t capacity = g.leafCapacity(), slots = g.slotCount();
    ASSERT_EQ(slots, 48u);
    ASSERT_LT(capacity, slots * 64u + slots * 62u * 3u);
    // Every leaf but two of every slot asks to split: within a slot leaf b weighs (1 + b)^3, a
    // table that cuts the second moment 2.05x (so it steers, and only such slots refine), shares
    // from 2.3e-7 to 0.061, leaves 2..63 above 4e-6. The largest go first.
    for (std::uint32_t s = 0; s < slots; ++s) {
        std::vector<double> r(64);
        for (int b = 0; b < 64; ++b)
            r[b] = 1000.0 * std::pow((1.0 + b) / 64.0, 3.0);
        writeSlot(*ctx, g, s, r, 100);
    }
    g.learn();
    const auto report = g.report();
    EXPECT_LE(g.leafCount(), capacity);
    EXPECT_GT(g.leafCount(), capacity - 3);
    EXPECT_GT(report["splits_deferred"].get<std::size_t>(), 0u);
    EXPECT_EQ(report["spatial_splits_last_pass"], 0u) << "6,400 contributions per voxel, but no room";
    // In every slot the leaves split are the heaviest: leaf b split implies leaf b + 1 split, the
    // heaviest (63) split, the lightest candidate (2: share 6.2e-6) waits.
    const FirstBounceGuide fresh(*ctx, o, glm::dvec3(0.0), 8.0);
    for (std::uint32_t s = 0; s < slots; ++s) {
        const auto now = g.leaves(s);
        const auto before = fresh.leaves(s);  // the initial 8 x 8, in the same order
        std::vector<bool> split(64);
        for (int b = 0; b < 64; ++b)
            split[b] = std::none_of(now.begin(), now.end(), [&](const auto& l) {
                return l.x0 == before[b].x0 && l.y0 == before[b].y0 && l.size == before[b].size;
            });
        EXPECT_TRUE(split[63]) << "slot " << s;
        EXPECT_FALSE(split[2]) << "slot " << s;
        for (int b = 0; b + 1 < 64; ++b)
            EXPECT_TRUE(!split[b] || split[b + 1]) << "slot " << s << ", leaf " << b;
    }
}

// The slots the device finds for points x with normals n.
std::vector<std::uint32_t> slotsOf(ocl::Context& ctx, const FirstBounceGuide& g, const std::vector<cl_float4>& x,
                                   const std::vector<cl_float4>& n)
{
    const auto count = static_cast<std::uint32_t>(x.size());
    cl::Buffer xb = ctx.buffer(CL_MEM_READ_ONLY, x.size() * 16, "points", const_cast<cl_float4*>(x.data()));
    cl::Buffer nb = ctx.buffer(CL_MEM_READ_ONLY, n.size() * 16, "normals", const_cast<cl_float4*>(n.data()));
    cl::Buffer sb = ctx.buffer(CL_MEM_WRITE_ONLY, x.size() * 4, "slots");
    cl::Kernel k(ctx.program("test_guide_probes.cl"), "guide_slot_probe");
    ocl::setKernelArgs(k, g.params(), g.tables(), xb, nb, count, sb);
    ocl::launch(ctx, k, "guide_slot_probe", count);
    std::vector<std::uint32_t> slot(x.size());
    ctx.queue().enqueueReadBuffer(sb, CL_TRUE, 0, slot.size() * 4, slot.data());
    return slot;
}

TEST(GuideSampling, SpaceSplitsWhereContributionsGatherAndTheDeviceFollows)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    GuideOptions o = options();
    o.spatialSplitConnections = 4096.0;
    FirstBounceGuide g(*ctx, o, glm::dvec3(0.0), 8.0);  // 8^3 voxels of 2 m from (-8, -8, -8)
    ASSERT_EQ(g.slotCount(), 6u * 512u);
    // The voxel [0, 2)^3 is voxel 4 + 8 (4 + 8 4) = 292; its +y side (2) is slot 6 292 + 2.
    const std::uint32_t voxel = 292, slot = 6 * voxel + 2;
    const std::vector<cl_float4> up = {{{0, 1, 0, 0}}, {{0, 1, 0, 0}}, {{0, 1, 0, 0}}, {{0, 1, 0, 0}}};
    const std::vector<cl_float4> x = {{{0.5f, 0.2f, 0.3f, 0}}, {{1.5f, 0.2f, 0.3f, 0}}, {{1.5f, 1.7f, 0.3f, 0}},
                                      {{1.5f, 1.7f, 1.9f, 0}}};
    for (std::uint32_t s : slotsOf(*ctx, g, x, up))
        ASSERT_EQ(s, slot) << "one voxel, one slot, before any split";
    // Two passes of 5,000 contributions in one slot, most of the light through its lowest corner
    // leaf (a table that steers: only there does space split): the voxel halves along x, then
    // (contributions in the upper-x half only) that half along y.
    const auto corner = [&](std::uint32_t sl) {
        std::vector<double> r;
        for (const auto& l : g.leaves(sl))
            r.push_back(l.x0 == 0.0 && l.y0 == 0.0 ? 400.0 : 1.0);
        return r;
    };
    writeSlot(*ctx, g, slot, corner(slot), 5000 / 64 + 1);
    g.learn();
    EXPECT_EQ(g.slotCount(), 6u * 513u);
    EXPECT_EQ(g.report()["spatial_splits_last_pass"], 1u);
    EXPECT_TRUE(g.learned(slot));
    std::vector<std::uint32_t> s = slotsOf(*ctx, g, x, up);
    EXPECT_EQ(s[0], slot) << "the lower half along x keeps the slot";
    EXPECT_EQ(s[1], 6u * 512u + 2u) << "the upper half gets the new spatial leaf's";
    EXPECT_EQ(s[2], s[1]);
    EXPECT_EQ(s[3], s[1]);
    writeSlot(*ctx, g, 6u * 512u + 2u, corner(6u * 512u + 2u), 5000 / 64 + 1);  // the upper-x half, now
    g.learn();
    s = slotsOf(*ctx, g, x, up);
    EXPECT_EQ(s[0], slot);
    EXPECT_EQ(s[1], 6u * 512u + 2u) << "y < 1 within the upper-x half";
    EXPECT_EQ(s[2], 6u * 513u + 2u) << "y >= 1: the newest leaf";
    EXPECT_EQ(s[3], s[2]);
    // Both halves of a split start from the parent's tree: the same table.
    const auto a = g.leaves(6u * 512u + 2u), b = g.leaves(6u * 513u + 2u);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i)
        EXPECT_EQ(a[i].probability, b[i].probability);
    // A checkpoint carries the spatial trees: the loaded guide finds the same slots.
    const auto h = resumed(*ctx, o, g);
    EXPECT_EQ(h->slotCount(), g.slotCount());
    EXPECT_EQ(slotsOf(*ctx, *h, x, up), s);
    EXPECT_EQ(h->report()["checksum"], g.report()["checksum"]);
}

TEST(GuideSampling, AGuideSplitToItsCapacityResumesFromItsOwnCheckpoint)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    GuideOptions o = options();
    o.voxelsAcross = 1;  // 8 voxels
    o.memoryMiB = 2.0;   // room for about 100 spatial leaves (94 with the default weight windows' bytes)
    FirstBounceGuide g(*ctx, o, glm::dvec3(0.0), 8.0);
    // Every slot steers (its light through one corner leaf) and gathers enough to split, pass
    // after pass, until the memory stops it.
    for (int pass = 0; pass < 6; ++pass) {
        for (std::uint32_t slot = 0; slot < g.slotCount(); ++slot) {
            std::vector<double> r;
            for (const auto& l : g.leaves(slot))
                r.push_back(l.x0 == 0.0 && l.y0 == 0.0 ? 400.0 : 1.0);
            writeSlot(*ctx, g, slot, r, 1000);
        }
        g.learn();
    }
    const auto report = g.report();
    // a spatial leaf holds at least six slots of the initial 64 leaves
    const double spatialCapacity = static_cast<double>(g.leafCapacity()) / (FEN_GUIDE_SIDES * 64.0);
    EXPECT_GT(static_cast<double>(g.spatialLeaves()), 0.78 * spatialCapacity)
        << "most of the capacity used by spatial splits";
    EXPECT_GT(report["spatial_splits_deferred"].get<std::size_t>() + report["splits_deferred"].get<std::size_t>(), 0u);
    const auto h = resumed(*ctx, o, g);
    EXPECT_EQ(h->slotCount(), g.slotCount());
    EXPECT_EQ(h->leafCount(), g.leafCount());
    EXPECT_EQ(h->report()["checksum"], report["checksum"]);
}

TEST(GuideSampling, StateThatDoesNotDescribeTreesIsAnErrorNamingTheField)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    GuideOptions o = options();
    o.voxelsAcross = 1;  // 8 voxels
    FirstBounceGuide g(*ctx, o, glm::dvec3(0.0), 8.0);
    const auto attempt = [&](const std::vector<std::uint64_t>& space, const std::vector<std::uint64_t>& slots,
                             const std::vector<std::uint64_t>& shape, const std::vector<double>& leaves,
                             std::vector<double> windows = {}) {
        if (windows.empty())
            windows.assign(3 * slots.size(), 0.0);
        StateWriter w;
        w.u64s("guide.space", space);
        w.u64s("guide.slots", slots);
        w.u64s("guide.shape", shape);
        w.f64s("guide.leaves", leaves);
        w.f64s("guide.windows", windows);
        w.u64s("guide.splits", {0, 0, 0, 0});
        StateReader r(w.bytes(), "bad.ckpt");
        try {
            g.load(r);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    std::vector<std::uint64_t> good;
    for (std::uint64_t v = 0; v < 8; ++v)
        good.insert(good.end(), {0, v});
    EXPECT_EQ(attempt(good, {}, {}, {}), "") << "the initial lattice loads";
    std::vector<std::uint64_t> twice = good;
    twice[3] = 0;  // voxel 1 claims spatial leaf 0 again
    EXPECT_NE(attempt(twice, {}, {}, {}).find("guide.space"), std::string::npos);
    std::vector<std::uint64_t> flag = good;
    flag[0] = 2;
    EXPECT_NE(attempt(flag, {}, {}, {}).find("guide.space"), std::string::npos);
    EXPECT_NE(attempt({0, 0}, {}, {}, {}).find("guide.space"), std::string::npos) << "seven voxels missing";
    std::vector<std::uint64_t> deep;  // voxel 0: a chain of nodes deeper than 9 halvings
    for (int k = 0; k < 12; ++k)
        deep.push_back(1);
    EXPECT_NE(attempt(deep, {}, {}, {}).find("guide.space"), std::string::npos);
    EXPECT_NE(attempt(good, {48}, {}, {}).find("guide.slots"), std::string::npos) << "slot 48 of 48";
    EXPECT_NE(attempt(good, {3}, {1, 1, 1, 1}, {}).find("guide.shape"), std::string::npos) << "a shape cut short";
    std::vector<std::uint64_t> leafy(4, 0);
    EXPECT_NE(attempt(good, {3}, leafy, {1.0, 1.0}).find("guide.leaves"), std::string::npos) << "3 leaves missing";
    // two totals a leaf (S, contributions)
    std::vector<double> totals(8, 0.0);
    totals[0] = totals[1] = 1.0;
    std::vector<double> negative = totals;
    negative[3] = -1.0;  // the second leaf's contributions
    EXPECT_NE(attempt(good, {3}, leafy, negative).find("guide.leaves"), std::string::npos);
    // three window totals a listed slot (delivered, arrived, visits)
    EXPECT_NE(attempt(good, {3}, leafy, totals, {1.0, -1.0, 1.0}).find("guide.windows"), std::string::npos);
    EXPECT_NE(attempt(good, {3}, leafy, totals, {1.0, 1.0}).find("guide.windows"), std::string::npos);
    // The guide is still whole after the failures: the last good state loads.
    EXPECT_EQ(attempt(good, {3}, leafy, totals), "");
    EXPECT_EQ(g.leaves(3).size(), 4u);
}

TEST(GuideSampling, VerticesOfOneVoxelAndSideShareASlot)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    FirstBounceGuide g(*ctx, options(), glm::dvec3(0.0), 8.0);  // voxels of 2 m from (-8, -8, -8)
    const std::vector<cl_float4> x = {{{0.01f, 0.02f, 0.03f, 0}}, {{1.24f, 1.2f, 0.1f, 0}}, {{0.1f, 0.1f, 0.1f, 0}},
                                      {{1e30f, -1e30f, 3.0f, 0}}};
    const std::vector<cl_float4> n = {{{0, 1, 0, 0}}, {{0.3f, 0.9f, 0.1f, 0}}, {{0, -1, 0, 0}}, {{1, 0, 0, 0}}};
    const std::vector<std::uint32_t> slot = slotsOf(*ctx, g, x, n);
    EXPECT_EQ(slot[0], slot[1]) << "one voxel, both facing +y mostly";
    EXPECT_EQ(slot[2], slot[0] + 1) << "the same voxel facing -y";
    // Far outside: the nearest voxel, (7, 0, 5), facing +x.
    EXPECT_EQ(slot[3], 6u * (7u + 8u * (0u + 8u * 5u)) + 0u);
    for (std::uint32_t s : slot)
        EXPECT_LT(s, g.slotCount());
}

}  // namespace
}  // namespace fen
