// camera_sampler_test.cpp — the camera pass's samples per pixel (render/camera_sampler.h) against
// the closed form of the balance it implements: n_p = round(sigma_p sqrt(T_L / (c V_L))), clamped to
// [floor, 4096] and to the light tracer's rays, sigma_p and c from the pilot; fixed mode never
// moves; the state round-trips; and the film's camera part (film.h BatchStatistics::addCamera) is
// each pixel's sample mean with the variance of its samples.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "io/state_io.h"
#include "render/camera_sampler.h"
#include "render/film.h"
#include "util/error.h"

namespace fen {
namespace {

// Runs the pilot passes with outputs in which pixel p's samples in each pass have squared
// deviations sigma[p]^2 (n - 1) about a mean of 0, `c` rays a sample in the first; returns what the
// sampler should have learned: sqrt(sum (n_i - 1) sigma^2 / (sum n_i - 1)) (the passes' means
// agree: nothing between them).
std::vector<double> pilot(CameraSampler& s, const std::vector<double>& sigma, double c)
{
    const std::size_t P = sigma.size();
    std::vector<double> within(P, 0.0), n(P, 0.0);
    for (int pass = 0; s.needsPilot(); ++pass) {
        std::vector<float> out(4 * P, 0.0f);
        for (std::size_t p = 0; p < P; ++p) {
            const double k = s.counts()[p];
            out[4 * p + 3] = static_cast<float>(sigma[p] * sigma[p] * std::max(0.0, k - 1.0));
            within[p] += sigma[p] * sigma[p] * std::max(0.0, k - 1.0);
            n[p] += k;
        }
        s.addPilot(out, pass == 0 ? static_cast<std::uint64_t>(c * s.samplesPerBatch()) : 0, P);
    }
    std::vector<double> learned(P);
    for (std::size_t p = 0; p < P; ++p)
        learned[p] = std::sqrt(within[p] / (n[p] - 1.0));
    return learned;
}

TEST(CameraSampler, FixedModeKeepsItsCount)
{
    CameraSampler s(8, 3, CameraPassMode::Fixed);
    EXPECT_FALSE(s.needsPilot());
    for (int b = 0; b < 4; ++b) {
        s.afterBatch(std::vector<double>(8, b % 2 ? 1.0 : 2.0), 1.0, 1000);
        for (std::uint32_t n : s.counts())
            EXPECT_EQ(n, 3u);
    }
    EXPECT_EQ(s.samplesTotal(), 4u * 8u * 3u);
}

TEST(CameraSampler, BalancedCountsFollowTheClosedForm)
{
    const std::size_t P = 6;
    CameraSampler s(P, 1, CameraPassMode::Balanced);
    ASSERT_TRUE(s.needsPilot());
    for (std::uint32_t n : s.counts())
        EXPECT_EQ(n, CameraSampler::kPilotSamples);
    const std::vector<double> sigma = {0.0, 2.0, 20.0, 50.0, 400.0, 1e6};
    const double c = 2.0;  // rays per sample
    const std::vector<double> learned = pilot(s, sigma, c);
    EXPECT_FALSE(s.needsPilot());
    for (std::uint32_t n : s.counts())
        EXPECT_EQ(n, 1u) << "before the light tracer's variance is known: the floor";
    // Light-traced images alternating by +-d per pixel: (L_b - L_{b-1})^2 = 4 d^2, weight 1 each, so
    // s^2 = 4 d^2 / 2 = 2 d^2 per pixel; V_L = P 2 d^2.
    const double d = 3.0;
    const std::uint64_t lightRays = 200000;
    s.afterBatch(std::vector<double>(P, 10.0 + d), 1.0, lightRays);
    for (std::uint32_t n : s.counts())
        EXPECT_EQ(n, 1u) << "one batch: the light tracer's variance is not known yet";
    s.afterBatch(std::vector<double>(P, 10.0 - d), 1.0, lightRays);
    const double VL = static_cast<double>(P) * 2.0 * d * d;
    const double k = std::sqrt(static_cast<double>(lightRays) / (c * VL));
    // The cap: the camera pass's rays at most the light tracer's, spare = T / c - floor P.
    double sigmaSum = 0.0;
    for (double v : learned)
        sigmaSum += v;
    const double kCapped = std::min(k, (static_cast<double>(lightRays) / c - P) / sigmaSum);
    ASSERT_LT(kCapped, k) << "the huge pixel makes the ray cap bind";
    for (std::size_t p = 0; p < P; ++p) {
        const double want = std::clamp(std::round(kCapped * learned[p]), 1.0, 4096.0);
        EXPECT_EQ(s.counts()[p], static_cast<std::uint32_t>(want)) << "pixel " << p;
    }
    EXPECT_EQ(s.counts()[0], 1u);     // no variance: the floor
    EXPECT_EQ(s.counts()[5], 4096u);  // the per-pixel cap
    EXPECT_EQ(s.maxCount(), 4096u);
}

TEST(CameraSampler, WithoutTheCapTheCountsAreTheOptimum)
{
    const std::size_t P = 4;
    CameraSampler s(P, 2, CameraPassMode::Balanced);
    const std::vector<double> sigma = {1.0, 30.0, 60.0, 90.0};
    const std::vector<double> learned = pilot(s, sigma, 1.0);  // one ray a sample
    const double d = 50.0;
    const std::uint64_t lightRays = 1000000;
    for (int b = 0; b < 2; ++b)
        s.afterBatch(std::vector<double>(P, b ? -d : d), 2.0, lightRays);
    // weights 2: E[(L_b - L_{b-1})^2] = s^2 (1/2 + 1/2) -> s^2 = 4 d^2 per pixel; next batch V = s^2 / 2.
    const double VL = static_cast<double>(P) * 4.0 * d * d / 2.0;
    const double k = std::sqrt(static_cast<double>(lightRays) / VL);
    for (std::size_t p = 0; p < P; ++p)
        EXPECT_EQ(s.counts()[p], static_cast<std::uint32_t>(std::max(2.0, std::round(k * learned[p]))));
    // Balanced: the camera pass's share of the variance is its share of the rays (up to rounding).
    double camVar = 0.0, camRays = 0.0;
    for (std::size_t p = 0; p < P; ++p) {
        camVar += learned[p] * learned[p] / s.counts()[p];
        camRays += s.counts()[p];
    }
    EXPECT_NEAR(camVar / VL, camRays / static_cast<double>(lightRays), 0.02 * camRays / lightRays);
    EXPECT_NEAR(s.errorShare(), camVar / (camVar + VL), 1e-12);
}

TEST(CameraSampler, ThePilotLooksAgainNextToWhatVaried)
{
    // A 4 x 3 image; only pixel (1, 1) varied in the first pass: its 8 neighbours get a second
    // look, the rest of the image none.
    const std::size_t W = 4, H = 3;
    CameraSampler s(W * H, 1, CameraPassMode::Balanced);
    std::vector<float> out(4 * W * H, 0.0f);
    out[4 * (1 * W + 1) + 3] = 7.0f * 100.0f;
    s.addPilot(out, s.samplesPerBatch(), W);
    ASSERT_TRUE(s.needsPilot());
    for (std::size_t y = 0; y < H; ++y)
        for (std::size_t x = 0; x < W; ++x) {
            const bool neighbour = x <= 2 && !(x == 1 && y == 1);
            EXPECT_EQ(s.counts()[y * W + x], neighbour ? CameraSampler::kPilotRefineSamples : 0u) << x << "," << y;
        }
    s.addPilot(std::vector<float>(4 * W * H, 0.0f), 0, W);
    EXPECT_FALSE(s.needsPilot());
    for (std::uint32_t n : s.counts())
        EXPECT_EQ(n, 1u);

    // Pixel (1, 1) bright (mean 100) and varying, its neighbours dark and agreeing in both passes:
    // each neighbour may hold a sliver of it, and gets the prior deviation 100 sqrt((N + 1) / ((N +
    // 2)(N + 3))), N = 8 + 24 samples; pixels beyond (x = 3) get nothing.
    CameraSampler t(W * H, 1, CameraPassMode::Balanced);
    std::vector<float> bright(4 * W * H, 0.0f);
    for (int c = 0; c < 3; ++c)
        bright[4 * (1 * W + 1) + c] = 100.0f;
    bright[4 * (1 * W + 1) + 3] = 7.0f * 100.0f;
    t.addPilot(bright, t.samplesPerBatch(), W);
    bright[4 * (1 * W + 1) + 3] = 23.0f * 100.0f;  // the second pass: 24 samples of the same
    t.addPilot(bright, 0, W);
    const double N = CameraSampler::kPilotSamples + CameraSampler::kPilotRefineSamples;
    const double prior = 100.0 * std::sqrt((N + 1.0) / ((N + 2.0) * (N + 3.0)));
    // Two batches of light (+-1 each pixel) set the counts: n = round(k sigma), k = sqrt(T / V_L).
    t.afterBatch(std::vector<double>(W * H, 1.0), 1.0, 1000000);
    t.afterBatch(std::vector<double>(W * H, -1.0), 1.0, 1000000);
    const double k = std::sqrt(1e6 / (W * H * 2.0));
    EXPECT_EQ(t.counts()[0], static_cast<std::uint32_t>(std::round(k * prior)));
    EXPECT_EQ(t.counts()[3], 1u);
}

TEST(CameraSampler, StateRoundTripsAndContinuesIdentically)
{
    const std::size_t P = 5;
    const std::vector<double> sigma = {0.0, 3.0, 9.0, 27.0, 81.0};
    CameraSampler a(P, 1, CameraPassMode::Balanced);
    pilot(a, sigma, 1.0);
    for (int b = 0; b < 3; ++b)
        a.afterBatch(std::vector<double>(P, b * 1.5), 1.0, 50000);
    StateWriter w;
    a.save(w);
    CameraSampler b(P, 1, CameraPassMode::Balanced);
    StateReader r(w.bytes(), "test");
    b.load(r);
    r.end();
    EXPECT_FALSE(b.needsPilot());
    EXPECT_EQ(a.counts(), b.counts());
    a.afterBatch(std::vector<double>(P, 7.0), 1.0, 80000);
    b.afterBatch(std::vector<double>(P, 7.0), 1.0, 80000);
    EXPECT_EQ(a.counts(), b.counts());
    EXPECT_EQ(a.samplesTotal(), b.samplesTotal());

    // A state for another image size, or with a count below the floor, is refused by key.
    CameraSampler other(P + 1, 1, CameraPassMode::Balanced);
    StateReader r2(w.bytes(), "test");
    EXPECT_THROW(other.load(r2), Error);
    CameraSampler higherFloor(P, 8, CameraPassMode::Balanced);
    StateReader r3(w.bytes(), "test");
    try {
        higherFloor.load(r3);
        ADD_FAILURE() << "a count below the floor was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("camera.counts"), std::string::npos) << e.what();
    }
}

TEST(CameraSampler, ModesByName)
{
    EXPECT_EQ(parseCameraPassMode("fixed"), CameraPassMode::Fixed);
    EXPECT_EQ(parseCameraPassMode("balanced"), CameraPassMode::Balanced);
    EXPECT_EQ(cameraPassModeName(parseCameraPassMode("balanced")), "balanced");
    EXPECT_THROW(parseCameraPassMode("adaptive"), Error);
}

TEST(CameraSampler, TheFilmAveragesTheCameraPartOverItsSamples)
{
    // One pixel, two batches: 1 sample of value 10, then 3 samples of mean 2 with squared
    // deviations 8 (values 0, 2, 4). All four samples: 10, 0, 2, 4 -> mean 4, variance 56/3.
    BatchStatistics st(1, 1, {Roi{0, 0, 1, 1}});
    st.add({1.0, 1.0, 1.0}, 1.0);
    st.addCamera({10.0f, 10.0f, 10.0f, 0.0f}, {1u});
    st.add({3.0, 3.0, 3.0}, 1.0);
    st.addCamera({2.0f, 2.0f, 2.0f, 8.0f}, {3u});
    EXPECT_NEAR(st.mean().rgb[0], 2.0 + 4.0, 1e-6);  // light part 2, camera part 4
    // light: batch spread (1 - 2)^2 + (3 - 2)^2 over 1, over W = 2 -> 1; camera: 56/3 / 4.
    EXPECT_NEAR(st.stdErrLuminance()[0], std::sqrt(1.0 + 56.0 / 3.0 / 4.0), 1e-9);
    const auto [m, v] = st.roiCamera(0);
    EXPECT_NEAR(m, 4.0, 1e-9);
    EXPECT_NEAR(v, 56.0 / 3.0 / 4.0, 1e-9);
}

}  // namespace
}  // namespace fen
