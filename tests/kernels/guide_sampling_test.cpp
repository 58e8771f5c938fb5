// guide_sampling_test.cpp — the first-bounce guide (DESIGN.md §3.4) against the density it claims:
// from statistics the test writes, learn() builds each slot's table as the documented mixture
// (1 - share) sqrt(S(b)) / sum sqrt(S) + share / 64 -- exactly, up to the integer table's 2^-32
// units -- and leaves uniform a slot with too few contributions and one whose table would not cut
// the second moment minGain times; the device then draws boxes with exactly the
// realised probabilities (chi-square, p > 1e-3, fixed seed), each point inside its box, with the
// density d(b) = 64 P(b) that the path's weight is divided by. Unbiasedness of the whole render
// with the guide on: Analytic.GuidedFirstBounceConservesEnergy.
#include <gtest/gtest.h>

#include <cmath>

#include "cl/launch.h"
#include "scatter/first_bounce_guide.h"
#include "support/cl_fixture.h"
#include "support/statistics.h"

namespace fen {
namespace {

constexpr std::uint32_t kSlots = 16;

GuideOptions options()
{
    GuideOptions o;
    o.enabled = true;
    o.slots = kSlots;
    o.share = 0.25;
    o.minConnections = 32.0;
    return o;
}

// Writes statistics for one slot, drawn so far with the cosine (d = 1): S(b) = r(b)^2, r in units of
// the device's v (scaled by 2^20, squared: 2^40), and a count per box.
void writeSlot(ocl::Context& ctx, const FirstBounceGuide& g, std::uint32_t slot, const std::vector<double>& r,
               std::uint64_t countPerBox)
{
    std::vector<std::uint64_t> words(FEN_GUIDE_BINS * FEN_GUIDE_STATS_WORDS, 0);
    for (int b = 0; b < FEN_GUIDE_BINS; ++b) {
        words[FEN_GUIDE_STATS_WORDS * b + FEN_GUIDE_SUMSQ_LO] = static_cast<std::uint64_t>(std::ldexp(r[b] * r[b], 40));
        words[FEN_GUIDE_STATS_WORDS * b + FEN_GUIDE_CONNECTIONS] = countPerBox;
    }
    ctx.queue().enqueueWriteBuffer(g.stats(), CL_TRUE, std::size_t{slot} * words.size() * 8, words.size() * 8,
                                   words.data());
}

TEST(GuideSampling, LearnedTableIsTheDocumentedMixtureAndTheDeviceDrawsIt)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    FirstBounceGuide g(*ctx, options(), glm::dvec3(0.0), 8.0);
    // Slot 5: two boxes carry nearly everything (the table predicts a 24x cut); slot 6: the same,
    // but no contributions counted yet; slot 7: a gentle ramp, a cut far below minGain = 2.
    std::vector<double> r(FEN_GUIDE_BINS, 1.0), ramp(FEN_GUIDE_BINS);
    r[9] = 400.0;
    r[10] = 200.0;
    double total = 0.0;
    for (int b = 0; b < FEN_GUIDE_BINS; ++b) {
        total += r[b];
        ramp[b] = 1.0 + 0.02 * b;
    }
    writeSlot(*ctx, g, 5, r, 1);     // 64 contributions: learned
    writeSlot(*ctx, g, 6, r, 0);     // none: stays the cosine
    writeSlot(*ctx, g, 7, ramp, 1);  // enough seen, too little to gain: stays the cosine
    g.learn();
    EXPECT_EQ(g.learnedSlots(), 1u);
    const std::vector<double> p = g.probabilities(5);
    for (int b = 0; b < FEN_GUIDE_BINS; ++b) {
        EXPECT_NEAR(p[b], 0.75 * r[b] / total + 0.25 / 64.0, 1e-8) << "box " << b;
        for (std::uint32_t slot : {6u, 7u})
            EXPECT_EQ(g.probabilities(slot)[b], 1.0 / 64.0) << "slot " << slot << ", box " << b;
    }
    // The statistics were cleared and the totals kept: another pass with nothing new changes nothing.
    g.learn();
    EXPECT_EQ(g.probabilities(5), p);

    const std::uint32_t n = 1u << 20;
    cl::Kernel k(ctx->program("test_guide_probes.cl"), "guide_sample_probe");
    cl::Buffer out = ctx->buffer(CL_MEM_WRITE_ONLY, std::size_t{n} * 16, "probe output");
    ocl::setKernelArgs(k, g.params(), g.tables(), std::uint32_t{5}, std::uint32_t{17}, n, out);
    ocl::launch(*ctx, k, "guide_sample_probe", n);
    std::vector<cl_float4> v(n);
    ctx->queue().enqueueReadBuffer(out, CL_TRUE, 0, std::size_t{n} * 16, v.data());
    std::vector<double> observed(FEN_GUIDE_BINS, 0.0), expected(FEN_GUIDE_BINS);
    int outside = 0, wrongDensity = 0;
    for (const cl_float4& s : v) {
        std::uint32_t key;
        std::memcpy(&key, &s.s[3], 4);
        ASSERT_EQ(key / FEN_GUIDE_BINS, 5u);
        const std::uint32_t b = key % FEN_GUIDE_BINS;
        observed[b] += 1.0;
        const double u1 = s.s[0] * 8.0, u2 = s.s[1] * 8.0;
        outside += !(u1 >= b % 8 && u1 < b % 8 + 1 && u2 >= b / 8 && u2 < b / 8 + 1 && s.s[0] < 1.0f && s.s[1] < 1.0f);
        wrongDensity += s.s[2] != static_cast<float>(64.0 * p[b]);
    }
    for (int b = 0; b < FEN_GUIDE_BINS; ++b)
        expected[b] = n * p[b];
    const double pv = test::chiSquarePValue(observed, expected);
    std::printf("[ guide ] boxes drawn against the realised table: chi-square p = %.3g\n", pv);
    EXPECT_GT(pv, 1e-3);
    EXPECT_EQ(outside, 0) << "points outside the box drawn";
    EXPECT_EQ(wrongDensity, 0) << "densities other than 64 P(b)";
}

TEST(GuideSampling, VerticesOfOneVoxelAndSideShareASlot)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    FirstBounceGuide g(*ctx, options(), glm::dvec3(0.0), 8.0);  // voxels of 0.25 m from (-8, -8, -8)
    const std::vector<cl_float4> x = {{{0.01f, 0.02f, 0.03f, 0}}, {{0.24f, 0.2f, 0.1f, 0}}, {{0.1f, 0.1f, 0.1f, 0}},
                                      {{1e30f, -1e30f, 3.0f, 0}}};
    const std::vector<cl_float4> n = {{{0, 1, 0, 0}}, {{0.3f, 0.9f, 0.1f, 0}}, {{0, -1, 0, 0}}, {{1, 0, 0, 0}}};
    const auto count = static_cast<std::uint32_t>(x.size());
    cl::Buffer xb = ctx->buffer(CL_MEM_READ_ONLY, x.size() * 16, "points", const_cast<cl_float4*>(x.data()));
    cl::Buffer nb = ctx->buffer(CL_MEM_READ_ONLY, n.size() * 16, "normals", const_cast<cl_float4*>(n.data()));
    cl::Buffer sb = ctx->buffer(CL_MEM_WRITE_ONLY, x.size() * 4, "slots");
    cl::Kernel k(ctx->program("test_guide_probes.cl"), "guide_slot_probe");
    ocl::setKernelArgs(k, g.params(), xb, nb, count, sb);
    ocl::launch(*ctx, k, "guide_slot_probe", count);
    std::vector<std::uint32_t> slot(x.size());
    ctx->queue().enqueueReadBuffer(sb, CL_TRUE, 0, slot.size() * 4, slot.data());
    EXPECT_EQ(slot[0], slot[1]) << "one voxel, both facing +y mostly";
    for (std::uint32_t s : slot)
        EXPECT_LT(s, kSlots);
}

}  // namespace
}  // namespace fen
