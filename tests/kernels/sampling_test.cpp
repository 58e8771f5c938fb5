// sampling_test.cpp — the device's sampling routines against their densities (chi-square, fixed
// seeds, p > 1e-3 required; Mitsuba's test03_chi2 idea), the sky sampler's weights against
// closed-form integrals (4 sigma of the sample's own standard error).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cl/launch.h"
#include "sky/sky_tables.h"
#include "util/integer_cdf.h"
#include "sky/goniogram.h"
#include "support/cl_fixture.h"
#include "support/render_support.h"
#include "support/statistics.h"

namespace fen {
namespace {

constexpr double kMinP = 1e-3;

std::vector<cl_float4> runSampling(ocl::Context& ctx, std::uint32_t n, std::uint32_t kind, float a,
                                   float b, std::uint32_t seed = 1)
{
    cl::Kernel k(ctx.program("test_probes.cl"), "sampling_probe");
    cl::Buffer out = ctx.buffer(CL_MEM_WRITE_ONLY, std::size_t{n} * 16, "samples");
    ocl::setKernelArgs(k, out, n, kind, a, b, seed);
    ocl::launch(ctx, k, "sampling_probe", n);
    std::vector<cl_float4> v(n);
    ctx.queue().enqueueReadBuffer(out, CL_TRUE, 0, v.size() * 16, v.data());
    return v;
}

// Histogram of (s, t) in [0,1)^2 on an nx x ny grid against a uniform expectation.
double uniformGridP(const std::vector<std::pair<double, double>>& st, int nx, int ny)
{
    std::vector<double> obs(static_cast<std::size_t>(nx * ny), 0.0);
    for (const auto& [s, t] : st) {
        const int i = std::clamp(static_cast<int>(s * nx), 0, nx - 1);
        const int j = std::clamp(static_cast<int>(t * ny), 0, ny - 1);
        obs[static_cast<std::size_t>(i * ny + j)] += 1.0;
    }
    const std::vector<double> exp(obs.size(), static_cast<double>(st.size()) / obs.size());
    return test::chiSquarePValue(obs, exp);
}

double phiFraction(double x, double z)
{
    double p = std::atan2(z, x) / (2.0 * M_PI);
    return p < 0.0 ? p + 1.0 : p;
}

TEST(Sampling, DiskIsUniform)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const auto v = runSampling(*ctx, 200000, 0, 0, 0);
    std::vector<std::pair<double, double>> st;
    for (const auto& s : v) {
        const double r2 = double(s.s[0]) * s.s[0] + double(s.s[1]) * s.s[1];
        ASSERT_LE(r2, 1.0 + 1e-6);
        st.push_back({r2, phiFraction(s.s[0], s.s[1])});  // uniform disk: r^2 and phi uniform
    }
    EXPECT_GT(uniformGridP(st, 10, 16), kMinP);
}

TEST(Sampling, CosineHemisphere)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const auto v = runSampling(*ctx, 200000, 1, 0, 0);
    std::vector<std::pair<double, double>> st;
    for (const auto& s : v) {
        const double y = s.s[1];
        ASSERT_GE(y, 0.0);
        ASSERT_NEAR(double(s.s[0]) * s.s[0] + y * y + double(s.s[2]) * s.s[2], 1.0, 1e-5);
        st.push_back({1.0 - y * y, phiFraction(s.s[0], s.s[2])});  // cos-weighted: sin^2 uniform
    }
    EXPECT_GT(uniformGridP(st, 10, 16), kMinP);
}

TEST(Sampling, ConeIsUniformInSolidAngle)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const float cosMax = std::cos(0.3f);
    const auto v = runSampling(*ctx, 200000, 2, cosMax, 0);
    std::vector<std::pair<double, double>> st;
    for (const auto& s : v) {
        ASSERT_GE(s.s[1], cosMax - 1e-6f);
        st.push_back({(1.0 - s.s[1]) / (1.0 - cosMax), phiFraction(s.s[0], s.s[2])});
    }
    EXPECT_GT(uniformGridP(st, 10, 16), kMinP);
}

TEST(Sampling, LinearDensity)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    for (const auto& [a, b] : std::vector<std::pair<float, float>>{{1, 3}, {2, 0}, {1, 1}, {0, 5}}) {
        const auto v = runSampling(*ctx, 100000, 3, a, b);
        const int bins = 20;
        std::vector<double> obs(bins, 0.0), exp(bins, 0.0);
        for (const auto& s : v) {
            ASSERT_GE(s.s[0], 0.0f);
            ASSERT_LT(s.s[0], 1.0f);
            obs[static_cast<std::size_t>(std::min(bins - 1, int(s.s[0] * bins)))] += 1.0;
        }
        for (int i = 0; i < bins; ++i) {
            // integral of (1-x) a + x b over the bin, normalised by (a + b) / 2
            const double x0 = double(i) / bins, x1 = double(i + 1) / bins;
            const auto F = [&](double x) { return a * (x - x * x / 2) + b * x * x / 2; };
            exp[static_cast<std::size_t>(i)] = (F(x1) - F(x0)) / ((a + b) / 2.0) * v.size();
        }
        EXPECT_GT(test::chiSquarePValue(obs, exp), kMinP) << "a=" << a << " b=" << b;
    }
}

TEST(Sampling, IntegerCdfChoosesWithExactProbabilities)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // Entries of very different sizes, some empty: empty ones must never be chosen, tiny ones must
    // keep a unit (tests/host/integer_cdf_test.cpp counts the units exactly).
    const std::vector<double> w = {5, 0, 1, 1e-12, 0, 30, 2, 2, 0, 7};
    const IntegerCdf t = makeIntegerCdf(w);
    EXPECT_GT(t.probability(3), 0.0) << "a tiny entry lost its light";
    const std::uint32_t n = 400000, cells = static_cast<std::uint32_t>(w.size());
    cl::Kernel k(ctx->program("test_probes.cl"), "cdf_probe");
    cl::Buffer ab = ctx->buffer(CL_MEM_READ_ONLY, t.alias.size() * 4, "alias", t.alias.data());
    cl::Buffer out = ctx->buffer(CL_MEM_WRITE_ONLY, n * 4, "choices");
    ocl::setKernelArgs(k, ab, t.aliasShift, out, n, std::uint32_t{3});
    ocl::launch(*ctx, k, "cdf_probe", n);
    std::vector<std::uint32_t> got(n);
    ctx->queue().enqueueReadBuffer(out, CL_TRUE, 0, n * 4, got.data());
    std::vector<double> obs(cells, 0.0), exp(cells, 0.0);
    for (auto c : got) {
        ASSERT_LT(c, cells);
        obs[c] += 1.0;
    }
    for (std::uint32_t i = 0; i < cells; ++i) {
        exp[i] = t.probability(i) * n;
        if (w[i] == 0.0) {
            EXPECT_EQ(obs[i], 0.0) << "empty entry " << i << " chosen";
        }
    }
    EXPECT_GT(test::chiSquarePValue(obs, exp), kMinP);
}

TEST(Sampling, IntegerCdfColumnEdgesExactly)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // Deterministic: both sides of every column's threshold and both ends of every column, against
    // the host's pick -- an off-by-one there has probability 2^-32 per draw, invisible to a
    // statistical test.
    const std::vector<double> w = {5, 0, 1, 1e-12, 0, 30, 2, 2, 0, 7, 1e-9, 3};
    const IntegerCdf t = makeIntegerCdf(w);
    const std::uint64_t C = std::uint64_t{1} << t.aliasShift;
    std::vector<std::uint32_t> r;
    for (std::uint64_t j = 0; j < t.alias.size() / 2; ++j) {
        const std::uint64_t base = j * C, thr = t.alias[2 * j];
        for (std::uint64_t v : {base, base + C - 1, base + thr - (thr > 0), base + thr - (thr == C)})
            r.push_back(static_cast<std::uint32_t>(v));
    }
    const auto n = static_cast<std::uint32_t>(r.size());
    cl::Kernel k(ctx->program("test_probes.cl"), "cdf_probe_at");
    cl::Buffer ab = ctx->buffer(CL_MEM_READ_ONLY, t.alias.size() * 4, "alias", t.alias.data());
    cl::Buffer rb = ctx->buffer(CL_MEM_READ_ONLY, n * 4, "values", r.data());
    cl::Buffer out = ctx->buffer(CL_MEM_WRITE_ONLY, n * 4, "entries");
    ocl::setKernelArgs(k, ab, t.aliasShift, rb, out, n);
    ocl::launch(*ctx, k, "cdf_probe_at", n);
    std::vector<std::uint32_t> got(n);
    ctx->queue().enqueueReadBuffer(out, CL_TRUE, 0, n * 4, got.data());
    for (std::uint32_t i = 0; i < n; ++i) {
        EXPECT_EQ(got[i], t.pick(r[i])) << "r = " << r[i];
        EXPECT_NE(w[got[i]], 0.0) << "empty entry drawn at r = " << r[i];
    }
}

struct SkyRun {
    std::vector<cl_float4> dirWeight;
    std::vector<float> lum;
};

// The sky alone (no sun): cells by their integral of g sin(theta), every direction's weight g / p.
struct SkySampler {
    SkyTables t;
    IntegerCdf cdf;
    std::vector<float> factor;
    explicit SkySampler(const Goniogram& g) : t(makeSkyTables(g)), cdf(makeIntegerCdf(t.cellSin))
    {
        for (std::uint32_t k = 0; k < t.cells; ++k)
            factor.push_back(static_cast<float>(t.cellFlat[k] / cdf.probability(k)));
    }
};

SkyRun runSky(ocl::Context& ctx, const SkySampler& s, std::uint32_t n)
{
    const SkyTables& t = s.t;
    cl::Kernel k(ctx.program("test_probes.cl"), "sky_probe");
    cl::Buffer th = ctx.buffer(CL_MEM_READ_ONLY, t.theta.size() * 4, "theta", t.theta.data());
    cl::Buffer ph = ctx.buffer(CL_MEM_READ_ONLY, t.phi.size() * 4, "phi", t.phi.data());
    cl::Buffer va = ctx.buffer(CL_MEM_READ_ONLY, t.values.size() * 4, "values", t.values.data());
    cl::Buffer al = ctx.buffer(CL_MEM_READ_ONLY, s.cdf.alias.size() * 4, "alias", s.cdf.alias.data());
    cl::Buffer fa = ctx.buffer(CL_MEM_READ_ONLY, s.factor.size() * 4, "factor", s.factor.data());
    cl::Buffer out = ctx.buffer(CL_MEM_WRITE_ONLY, std::size_t{n} * 16, "dirs");
    cl::Buffer lum = ctx.buffer(CL_MEM_WRITE_ONLY, std::size_t{n} * 4, "lum");
    ocl::setKernelArgs(k, th, ph, va, al, s.cdf.aliasShift, fa, t.thetaNodes, t.phiNodes, out,
                       lum, n, std::uint32_t{5});
    ocl::launch(ctx, k, "sky_probe", n);
    SkyRun r;
    r.dirWeight.resize(n);
    r.lum.resize(n);
    ctx.queue().enqueueReadBuffer(out, CL_TRUE, 0, r.dirWeight.size() * 16, r.dirWeight.data());
    ctx.queue().enqueueReadBuffer(lum, CL_TRUE, 0, r.lum.size() * 4, r.lum.data());
    return r;
}

// Directions drawn from g's cells, binned 2 x 2 per cell, against the bilinear function's mass;
// and the device's luminance lookup in each against the host's.
void expectSkyDirectionsFollowCellByCell(ocl::Context& ctx, const Goniogram& g)
{
    const SkySampler sampler(g);
    const SkyTables& t = sampler.t;
    const std::uint32_t n = 400000;
    const SkyRun r = runSky(ctx, sampler, n);
    // Bins: each cell split 2 x 2; the expected mass of a sub-rectangle is the cell's probability
    // times the bilinear function's share there (exact: bilinear integrals).
    const std::size_t nt = t.thetaNodes, np = t.phiNodes;
    std::vector<double> obs((nt - 1) * (np - 1) * 4, 0.0), exp(obs.size(), 0.0);
    const auto& TH = g.theta();
    const auto& PH = g.phi();
    for (const auto& s : r.dirWeight) {
        double theta, phi;
        skyAngles(glm::dvec3(s.s[0], s.s[1], s.s[2]), &theta, &phi);
        const std::size_t i = std::upper_bound(TH.begin(), TH.end(), theta) - TH.begin() - 1;
        const std::size_t j = std::upper_bound(PH.begin(), PH.end(), phi) - PH.begin() - 1;
        const std::size_t ii = std::min(i, nt - 2), jj = std::min(j, np - 2);
        const int si = (theta - TH[ii]) / (TH[ii + 1] - TH[ii]) >= 0.5 ? 1 : 0;
        const int sj = (phi - PH[jj]) / (PH[jj + 1] - PH[jj]) >= 0.5 ? 1 : 0;
        obs[((ii * (np - 1) + jj) * 2 + si) * 2 + sj] += 1.0;
    }
    for (std::size_t i = 0; i + 1 < nt; ++i)
        for (std::size_t j = 0; j + 1 < np; ++j) {
            const std::size_t k = i * (np - 1) + j;
            const double pk = sampler.cdf.probability(k);
            const double g00 = g.value(i, j), g01 = g.value(i, j + 1), g10 = g.value(i + 1, j),
                         g11 = g.value(i + 1, j + 1);
            // integral of the bilinear over [a0,a1] x [b0,b1] in unit cell coordinates
            auto mass = [&](double a0, double a1, double b0, double b1) {
                auto I = [](double x0, double x1, int deg) {
                    return deg == 0 ? (x1 - x0) - (x1 * x1 - x0 * x0) / 2 : (x1 * x1 - x0 * x0) / 2;
                };
                return g00 * I(a0, a1, 0) * I(b0, b1, 0) + g01 * I(a0, a1, 0) * I(b0, b1, 1) +
                       g10 * I(a0, a1, 1) * I(b0, b1, 0) + g11 * I(a0, a1, 1) * I(b0, b1, 1);
            };
            const double whole = mass(0, 1, 0, 1);
            for (int si = 0; si < 2; ++si)
                for (int sj = 0; sj < 2; ++sj)
                    exp[(k * 2 + si) * 2 + sj] =
                        n * pk * mass(0.5 * si, 0.5 * si + 0.5, 0.5 * sj, 0.5 * sj + 0.5) / whole;
        }
    EXPECT_GT(test::chiSquarePValue(obs, exp), kMinP);
    // The device's luminance lookup agrees with the host's bilinear goniogram.
    for (std::size_t i = 0; i < 2000; ++i) {
        const auto& s = r.dirWeight[i];
        const double host = g.evalDirection(glm::dvec3(s.s[0], s.s[1], s.s[2]));
        EXPECT_NEAR(r.lum[i], host, 1e-4 * host + 1e-3);
    }
}

TEST(Sampling, SkyDirectionsFollowTheGoniogramCellByCell)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    expectSkyDirectionsFollowCellByCell(*ctx, test::unevenTableSky());
}

TEST(Sampling, SkyWithAGroundFollowsItsTableOverTheWholeSphere)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // The ground's rows below the horizon are cells like the sky's; the zero-width cell of the
    // horizon's step has probability 0.
    expectSkyDirectionsFollowCellByCell(*ctx, test::unevenTableSky().withGround(300.0));
}

TEST(Sampling, SkyWithAGroundWeightsIntegrateBothHemispheres)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // E[w] = ∫ g dω over the sphere, E[w max(0, y)] the sky's horizontal illuminance and
    // E[w max(0, -y)] = pi L_g (the ground's, facing down); every draw below the horizon looks up
    // L_g on the device. 4 sigma of the sample standard error.
    for (const Goniogram& g : {test::unevenTableSky().withGround(300.0), uniformSky(1234.0).withGround(777.0)}) {
        const SkyRun r = runSky(*ctx, SkySampler(g), 400000);
        std::vector<double> w, up, down;
        std::size_t below = 0;
        for (std::size_t i = 0; i < r.dirWeight.size(); ++i) {
            const auto& s = r.dirWeight[i];
            w.push_back(s.s[3]);
            up.push_back(s.s[3] * std::max(0.0f, s.s[1]));
            down.push_back(s.s[3] * std::max(0.0f, -s.s[1]));
            if (s.s[1] < 0.0f) {
                ++below;
                EXPECT_EQ(r.lum[i], static_cast<float>(g.groundLuminance())) << i;
            }
        }
        const auto a = test::meanAndStdErr(w), b = test::meanAndStdErr(up), c = test::meanAndStdErr(down);
        const double Ed = g.illuminance(glm::dvec3(0, -1, 0));
        EXPECT_NEAR(Ed, M_PI * g.groundLuminance(), 1e-9 * Ed);
        std::printf("[ sampling ] ground %g: integral %+.2f sigma, up %+.2f sigma, down %+.2f sigma\n",
                    g.groundLuminance(), (a.mean - g.integral()) / a.se,
                    (b.mean - g.illuminance(glm::dvec3(0, 1, 0))) / b.se, (c.mean - Ed) / c.se);
        EXPECT_NEAR(a.mean, g.integral(), 4.0 * a.se) << "relative se " << a.se / a.mean;
        EXPECT_NEAR(b.mean, g.illuminance(glm::dvec3(0, 1, 0)), 4.0 * b.se);
        EXPECT_NEAR(c.mean, Ed, 4.0 * c.se);
        EXPECT_LT(a.se / a.mean, 2e-3) << "the sampler should give nearly constant weights";
        EXPECT_GT(below, r.dirWeight.size() / 10);
    }
}

TEST(Sampling, SkyWeightsIntegrateTheSky)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // E[w] = ∫ g dω and E[w cos θ] = ∫ g cos θ dω (horizontal illuminance): the path weights are
    // g/p for the procedure's exact density. 4 sigma of the sample standard error.
    for (const Goniogram& g : {test::unevenTableSky(), uniformSky(1234.0)}) {
        const SkyRun r = runSky(*ctx, SkySampler(g), 400000);
        std::vector<double> w, wc;
        for (const auto& s : r.dirWeight) {
            w.push_back(s.s[3]);
            wc.push_back(s.s[3] * s.s[1]);
        }
        const auto a = test::meanAndStdErr(w), b = test::meanAndStdErr(wc);
        EXPECT_NEAR(a.mean, g.integral(), 4.0 * a.se) << "relative se " << a.se / a.mean;
        EXPECT_NEAR(b.mean, g.illuminance(glm::dvec3(0, 1, 0)), 4.0 * b.se);
        EXPECT_LT(a.se / a.mean, 2e-3) << "the sampler should give nearly constant weights";
    }
}

TEST(Sampling, FresnelMatchesTheHostFormula)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    std::vector<float> c;
    for (int i = 0; i <= 1000; ++i)
        c.push_back((i % 2 ? -1.0f : 1.0f) * i / 1000.0f);
    const auto n = static_cast<std::uint32_t>(c.size());
    cl::Kernel k(ctx->program("test_probes.cl"), "fresnel_probe");
    cl::Buffer in = ctx->buffer(CL_MEM_READ_ONLY, n * 4, "cos", c.data());
    cl::Buffer out = ctx->buffer(CL_MEM_WRITE_ONLY, n * 4, "R");
    const float eta = 1.5f;
    ocl::setKernelArgs(k, in, out, n, eta);
    ocl::launch(*ctx, k, "fresnel_probe", n);
    std::vector<float> R(n);
    ctx->queue().enqueueReadBuffer(out, CL_TRUE, 0, n * 4, R.data());
    for (std::uint32_t i = 0; i < n; ++i) {
        const double ci = std::fabs(c[i]), st2 = (1 - ci * ci) / (1.5 * 1.5), ct = std::sqrt(1 - st2);
        const double rs = (ci - 1.5 * ct) / (ci + 1.5 * ct), rp = (1.5 * ci - ct) / (1.5 * ci + ct);
        EXPECT_NEAR(R[i], 0.5 * (rs * rs + rp * rp), 2e-6) << "cos " << c[i];
    }
    EXPECT_NEAR(R[0], 1.0f, 1e-6);                       // grazing: total reflection
    EXPECT_NEAR(R[n - 1], 0.04f, 1e-6);                  // normal: ((1.5-1)/(1.5+1))^2
}

// lib/trig.h's polynomials against double precision: sin(pi t), cos(pi t) over the ranges the
// samplers use ([0, 2] and [-1, 1]) and a few turns beyond, acos over [-1, 1] with its ends. The
// bounds are the ones trig.h states (1.0e-7, 2.2e-7, 4.1e-7), measured with float arithmetic in
// the polynomials' fit; a coefficient of the wrong sign or a wrong quadrant misses them by orders of magnitude.
TEST(Trig, PolynomialsMatchDoublePrecision)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    std::vector<float> t;
    for (int i = -16384; i <= 16384; ++i)
        t.push_back(static_cast<float>(i) / 4096.0f); // every quarter turn's edges, in [-4, 4]
    std::uint64_t x = 0x9E3779B97F4A7C15ull;
    for (int i = 0; i < 200000; ++i) {
        x = x * 6364136223846793005ull + 1442695040888963407ull;
        t.push_back(static_cast<float>(static_cast<double>(x >> 40) / 16777216.0 * 2.0 - 1.0) * (i % 2 ? 1.0f : 2.0f));
    }
    for (float e : {1.0f, -1.0f, 0.0f, 0.5f, -0.5f, 0.25f, 1.0f - 0x1p-24f, -1.0f + 0x1p-24f, 0x1p-20f})
        t.push_back(e);
    const auto n = static_cast<std::uint32_t>(t.size());
    cl::Kernel k(ctx->program("test_probes.cl"), "trig_probe");
    cl::Buffer in = ctx->buffer(CL_MEM_READ_ONLY, n * 4, "t", t.data());
    cl::Buffer out = ctx->buffer(CL_MEM_WRITE_ONLY, std::size_t{n} * 16, "trig");
    ocl::setKernelArgs(k, in, out, n);
    ocl::launch(*ctx, k, "trig_probe", n);
    std::vector<cl_float4> r(n);
    ctx->queue().enqueueReadBuffer(out, CL_TRUE, 0, r.size() * 16, r.data());
    double worstSin = 0.0, worstCos = 0.0, worstNorm = 0.0, worstAcos = 0.0;
    for (std::uint32_t i = 0; i < n; ++i) {
        const double ti = t[i], s = r[i].s[0], c = r[i].s[1];
        worstSin = std::max(worstSin, std::fabs(s - std::sin(M_PI * ti)));
        worstCos = std::max(worstCos, std::fabs(c - std::cos(M_PI * ti)));
        worstNorm = std::max(worstNorm, std::fabs(s * s + c * c - 1.0));
        if (std::fabs(ti) <= 1.0)
            worstAcos = std::max(worstAcos, std::fabs(r[i].s[2] - std::acos(ti)));
    }
    std::printf("[ trig     ] worst |error|: sin %.3g, cos %.3g, s^2+c^2-1 %.3g, acos %.3g\n", worstSin, worstCos,
                worstNorm, worstAcos);
    EXPECT_LE(worstSin, 1.0e-7);
    EXPECT_LE(worstCos, 1.0e-7);
    EXPECT_LE(worstNorm, 2.2e-7);
    EXPECT_LE(worstAcos, 4.1e-7);
    EXPECT_EQ(r[n - 9].s[2], 0.0f);  // acos(1) exactly 0
    EXPECT_EQ(r[n - 9].s[0], 0.0f);  // sin(pi) exactly 0 (t = 1 reduces to r = 0)
    EXPECT_EQ(r[n - 7].s[1], 1.0f);  // cos(0) exactly 1
}

}  // namespace
}  // namespace fen
