// sky_test.cpp — the sky model (host/sky, DESIGN.md §1 "Sky", §6): the goniogram's checks,
// bilinear evaluation and exact integrals against brute-force quadrature; the uniform sky's
// closed forms; the user table's errors; the CIE general sky against its formula, a published
// special case, its symmetry, and the 0.1 % interpolation requirement.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <random>

#include <glm/geometric.hpp>

#include "support/error_of.h"
#include "sky/cie_sky.h"
#include "sky/goniogram.h"
#include "sky/sky_tables.h"
#include "shared/fen_render.h"
#include "util/error.h"

namespace fen {
namespace {

constexpr double kHalfPi = M_PI / 2;
constexpr double kTwoPi = 2 * M_PI;
constexpr double kDeg = M_PI / 180;

using test::errorOf;

bool startsWith(const std::string& s, const std::string& prefix)
{
    return s.rfind(prefix, 0) == 0;
}
bool contains(const std::string& s, const std::string& part)
{
    return s.find(part) != std::string::npos;
}

// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n).
struct Gauss {
    std::vector<double> x, w;
    explicit Gauss(int n) : x(n), w(n)
    {
        for (int i = 0; i < n; ++i) {
            double z = std::cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 0;
            for (int it = 0; it < 100; ++it) {
                double p0 = 1, p1 = z;
                for (int k = 2; k <= n; ++k) {
                    const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n * (z * p1 - p0) / (z * z - 1);
                const double dz = p1 / dp;
                z -= dz;
                if (std::abs(dz) < 1e-16)
                    break;
            }
            x[i] = z;
            w[i] = 2 / ((1 - z * z) * dp * dp);
        }
    }
    // ∫_a^b h, composite over `parts` pieces
    double integrate(double a, double b, int parts, const std::function<double(double)>& h) const
    {
        double sum = 0;
        for (int p = 0; p < parts; ++p) {
            const double lo = a + (b - a) * p / parts, hi = a + (b - a) * (p + 1) / parts;
            for (std::size_t i = 0; i < x.size(); ++i)
                sum += w[i] * 0.5 * (hi - lo) * h(0.5 * (lo + hi) + 0.5 * (hi - lo) * x[i]);
        }
        return sum;
    }
};

// A valid goniogram on an uneven grid with random values, including a sliver cell and a cell at
// the pole, so that the integrals are tested where cancellation would bite.
Goniogram randomGoniogram(unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const std::vector<double> th = {0, 1e-6, 0.05, 0.3, 0.31, 0.9, 1.4, 1.5707, kHalfPi};
    const std::vector<double> ph = {0, 0.2, 0.2 + 1e-7, 1.1, 2.5, 4.0, 5.9, kTwoPi};
    std::vector<double> v(th.size() * ph.size());
    for (double& x : v)
        x = 100 * u(rng);
    for (std::size_t j = 0; j < ph.size(); ++j)
        v[j] = v[0];
    for (std::size_t i = 0; i < th.size(); ++i)
        v[i * ph.size() + ph.size() - 1] = v[i * ph.size()];
    return Goniogram(th, ph, v, "random");
}

// ---------------------------------------------------------------------------------------------
// Goniogram

TEST(Goniogram, ConstructorRejectsEachBrokenRule)
{
    const std::vector<double> th = {0, 0.5, kHalfPi}, ph = {0, 3, kTwoPi};
    const std::vector<double> ok(9, 1.0);
    auto err = [](std::vector<double> t, std::vector<double> p, std::vector<double> v) {
        return errorOf([&] { Goniogram(t, p, v, "where-tag"); });
    };
    EXPECT_EQ(err(th, ph, ok), "(no error)");
    std::vector<std::pair<std::string, std::string>> cases = {
        {err({0}, ph, std::vector<double>(3, 1.0)), "at least 2"},
        {err({0.1, 0.5, kHalfPi}, ph, ok), "start at exactly 0"},
        {err({0, 0.5, 1.5}, ph, ok), "end at exactly pi/2"},
        {err({0, 0.5, 0.5, kHalfPi}, ph, std::vector<double>(12, 1.0)), "strictly increasing"},
        {err({0, 0.7, 0.5, kHalfPi}, ph, std::vector<double>(12, 1.0)), "strictly increasing"},
        {err({0, NAN, kHalfPi}, ph, ok), "not finite"},
        {err(th, {0, 3, 6}, ok), "end at exactly 2 pi"},
        {err(th, {0, 3, 3, kTwoPi}, std::vector<double>(12, 1.0)), "strictly increasing"},
        {err(th, ph, std::vector<double>(8, 1.0)), "has 8 values, expected 3 x 3 = 9"},
        {err(th, ph, {1, 1, 1, 1, -2, 1, 1, 1, 1}), "negative"},
        {err(th, ph, {1, 1, 1, 1, NAN, 1, 1, 1, 1}), "not finite"},
        {err(th, ph, {1, 1, 1, 1, INFINITY, 1, 1, 1, 1}), "not finite"},
        {err(th, ph, {1, 1, 1, 2, 1, 3, 1, 1, 1}), "phi = 0 and phi = 2 pi"},
        {err(th, ph, {1, 2, 1, 1, 1, 1, 1, 1, 1}), "theta = 0 is one direction"},
    };
    for (const auto& [message, part] : cases) {
        EXPECT_TRUE(startsWith(message, "where-tag: ")) << message;
        EXPECT_TRUE(contains(message, part)) << message << "  -- expected: " << part;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

TEST(Goniogram, EvalAtNodesIsExact)
{
    const Goniogram g = randomGoniogram(1);
    for (std::size_t i = 0; i < g.thetaCount(); ++i)
        for (std::size_t j = 0; j < g.phiCount(); ++j)
            EXPECT_EQ(g.eval(g.theta()[i], g.phi()[j]), g.value(i, j)) << i << " " << j;
}

TEST(Goniogram, EvalIsBilinearInsideCells)
{
    const Goniogram g = randomGoniogram(2);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (std::size_t i = 0; i + 1 < g.thetaCount(); ++i)
        for (std::size_t j = 0; j + 1 < g.phiCount(); ++j) {
            const double t0 = g.theta()[i], t1 = g.theta()[i + 1], p0 = g.phi()[j],
                         p1 = g.phi()[j + 1];
            const double v00 = g.value(i, j), v01 = g.value(i, j + 1), v10 = g.value(i + 1, j),
                         v11 = g.value(i + 1, j + 1);
            const double scale = std::max({v00, v01, v10, v11});
            EXPECT_NEAR(g.eval(0.5 * (t0 + t1), 0.5 * (p0 + p1)), 0.25 * (v00 + v01 + v10 + v11),
                        1e-9 * scale);
            for (int k = 0; k < 5; ++k) {
                const double s = u(rng), w = u(rng);
                const double expect =
                    (1 - s) * (1 - w) * v00 + (1 - s) * w * v01 + s * (1 - w) * v10 + s * w * v11;
                EXPECT_NEAR(g.eval(t0 + s * (t1 - t0), p0 + w * (p1 - p0)), expect, 1e-9 * scale);
            }
        }
}

TEST(Goniogram, PhiWrapsAroundAndNothingBelowTheHorizon)
{
    const Goniogram g = randomGoniogram(4);
    for (double t : {0.0, 0.2, 1.0, kHalfPi})
        for (double p : {0.0, 0.1, 3.0, 6.2}) {
            const double v = g.eval(t, p);
            EXPECT_NEAR(g.eval(t, p + kTwoPi), v, 1e-9 * v);
            EXPECT_NEAR(g.eval(t, p - kTwoPi), v, 1e-9 * v);
            EXPECT_NEAR(g.eval(t, p + 5 * kTwoPi), v, 1e-9 * v);
        }
    // Just below 2 pi is the last cell, which closes onto the phi = 0 column.
    EXPECT_NEAR(g.eval(1.0, kTwoPi - 1e-12), g.eval(1.0, 0.0), 1e-9);
    EXPECT_NEAR(g.eval(1.0, -1e-12), g.eval(1.0, 0.0), 1e-9);
    EXPECT_EQ(g.eval(kHalfPi + 1e-12, 1.0), 0.0);
    EXPECT_EQ(g.eval(2.0, 1.0), 0.0);
    EXPECT_EQ(g.evalDirection({0.3, -1e-9, 0.2}), 0.0);
    EXPECT_EQ(g.evalDirection({0, -1, 0}), 0.0);
    EXPECT_GT(g.evalDirection({1, 0, 0}), 0.0);  // the horizon itself is sky
}

TEST(Goniogram, DirectionsFollowTheFrame)
{
    // y up, azimuth from north (-z) towards east (+x).
    auto near = [](glm::dvec3 a, glm::dvec3 b) { return glm::length(a - b) < 1e-15; };
    EXPECT_TRUE(near(skyDirection(0, 1.234), {0, 1, 0}));
    EXPECT_TRUE(near(skyDirection(kHalfPi, 0), {0, 0, -1}));            // north
    EXPECT_TRUE(near(skyDirection(kHalfPi, kHalfPi), {1, 0, 0}));       // east
    EXPECT_TRUE(near(skyDirection(kHalfPi, M_PI), {0, 0, 1}));          // south
    EXPECT_TRUE(near(skyDirection(kHalfPi, 3 * kHalfPi), {-1, 0, 0}));  // west
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const Goniogram g = randomGoniogram(6);
    for (int k = 0; k < 200; ++k) {
        const double t = kHalfPi * u(rng), p = kTwoPi * u(rng), len = 0.1 + 10 * u(rng);
        double t2, p2;
        skyAngles(len * skyDirection(t, p), &t2, &p2);
        EXPECT_NEAR(t2, t, 1e-12);
        EXPECT_NEAR(std::remainder(p2 - p, kTwoPi), 0.0, 1e-12);
        EXPECT_GE(p2, 0.0);
        EXPECT_LT(p2, kTwoPi);
        const double v = g.eval(t, p);
        EXPECT_NEAR(g.evalDirection(len * skyDirection(t, p)), v, 1e-9 * (1 + v));
    }
}

TEST(Goniogram, CellIntegralsMatchQuadrature)
{
    const Goniogram g = randomGoniogram(7);
    const Gauss gauss(12);
    for (std::size_t i = 0; i + 1 < g.thetaCount(); ++i)
        for (std::size_t j = 0; j + 1 < g.phiCount(); ++j) {
            const double t0 = g.theta()[i], t1 = g.theta()[i + 1], p0 = g.phi()[j],
                         p1 = g.phi()[j + 1];
            // Quadrature of eval itself at interior points, 4 x 12 points per axis.
            auto quad = [&](const std::function<double(double, double)>& weight) {
                return gauss.integrate(t0, t1, 4, [&](double t) {
                    return gauss.integrate(p0, p1, 4,
                                           [&](double p) { return g.eval(t, p) * weight(t, p); });
                });
            };
            const double flat = quad([](double, double) { return 1.0; });
            const double withSin = quad([](double t, double) { return std::sin(t); });
            const glm::dvec3 dir(
                quad([](double t, double p) { return std::sin(t) * std::sin(t) * std::sin(p); }),
                quad([](double t, double) { return std::sin(t) * std::cos(t); }),
                quad([](double t, double p) { return -std::sin(t) * std::sin(t) * std::cos(p); }));
            SCOPED_TRACE(testing::Message() << "cell " << i << ", " << j);
            EXPECT_NEAR(g.cellIntegralFlat(i, j), flat, 1e-11 * std::abs(flat) + 1e-300);
            EXPECT_NEAR(g.cellIntegralSin(i, j), withSin, 1e-10 * std::abs(withSin) + 1e-300);
            const glm::dvec3 f = g.cellDirectionIntegral(i, j);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(f[c], dir[c], 1e-9 * withSin + 1e-300) << "component " << c;
        }
}

TEST(Goniogram, IlluminanceIsExactWhereThePlaneDoesNotCut)
{
    // Facing straight up no cell is cut: E = sum of F . n, checked by quadrature per cell.
    const Goniogram g = randomGoniogram(8);
    const Gauss gauss(12);
    double quad = 0;
    for (std::size_t i = 0; i + 1 < g.thetaCount(); ++i)
        for (std::size_t j = 0; j + 1 < g.phiCount(); ++j)
            quad += gauss.integrate(g.theta()[i], g.theta()[i + 1], 4, [&](double t) {
                return gauss.integrate(g.phi()[j], g.phi()[j + 1], 4, [&](double p) {
                    return g.eval(t, p) * std::cos(t) * std::sin(t);
                });
            });
    EXPECT_NEAR(g.illuminance({0, 1, 0}), quad, 1e-10 * quad);
    EXPECT_NEAR(g.illuminance({0, 7, 0}), quad, 1e-10 * quad);  // normal of any length
    EXPECT_EQ(g.illuminance({0, -1, 0}), 0.0);
}

TEST(Goniogram, IlluminanceOfCutPlanesIsConsistent)
{
    // max(0, x) - max(0, -x) = x: E(n) - E(-n) = (sum of F_ij) . n exactly, whatever the cut.
    const Goniogram g = randomGoniogram(9);
    glm::dvec3 total(0);
    for (std::size_t i = 0; i + 1 < g.thetaCount(); ++i)
        for (std::size_t j = 0; j + 1 < g.phiCount(); ++j)
            total += g.cellDirectionIntegral(i, j);
    std::mt19937 rng(10);
    std::normal_distribution<double> nd;
    for (int k = 0; k < 6; ++k) {
        const glm::dvec3 n = glm::normalize(glm::dvec3(nd(rng), nd(rng), nd(rng)));
        const double plus = g.illuminance(n), minus = g.illuminance(-n);
        EXPECT_NEAR(plus - minus, glm::dot(total, n), 1e-7 * (plus + minus));
        // and against a midpoint rule with N x N points per cell, N = 32 and 64, Richardson-
        // extrapolated (it converges as N^-2, slowly, because of the kink along the cut)
        auto midpoint = [&](int N) {
            double quad = 0;
            for (std::size_t i = 0; i + 1 < g.thetaCount(); ++i)
                for (std::size_t j = 0; j + 1 < g.phiCount(); ++j) {
                    const double t0 = g.theta()[i], dt = (g.theta()[i + 1] - t0) / N;
                    const double p0 = g.phi()[j], dp = (g.phi()[j + 1] - p0) / N;
                    for (int a = 0; a < N; ++a)
                        for (int b = 0; b < N; ++b) {
                            const double t = t0 + (a + 0.5) * dt, p = p0 + (b + 0.5) * dp;
                            quad += g.eval(t, p) * std::max(0.0, glm::dot(skyDirection(t, p), n)) *
                                    std::sin(t) * dt * dp;
                        }
                }
            return quad;
        };
        const double quad = (4 * midpoint(64) - midpoint(32)) / 3;
        EXPECT_NEAR(plus, quad, 2e-5 * quad);
    }
}

TEST(Goniogram, RefinedIsTheSameFunction)
{
    const Goniogram g = randomGoniogram(11);
    const Goniogram r = g.refined(0.01, 0.1);
    for (std::size_t i = 0; i + 1 < r.thetaCount(); ++i)
        EXPECT_LE(r.theta()[i + 1] - r.theta()[i], 0.01 * (1 + 1e-12));
    for (std::size_t j = 0; j + 1 < r.phiCount(); ++j)
        EXPECT_LE(r.phi()[j + 1] - r.phi()[j], 0.1 * (1 + 1e-12));
    for (double t : g.theta())  // old nodes stay nodes
        EXPECT_TRUE(std::find(r.theta().begin(), r.theta().end(), t) != r.theta().end());
    std::mt19937 rng(12);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int k = 0; k < 2000; ++k) {
        const double t = kHalfPi * u(rng), p = kTwoPi * u(rng);
        EXPECT_NEAR(r.eval(t, p), g.eval(t, p), 1e-12 * 100);
    }
    EXPECT_NEAR(r.integral(), g.integral(), 1e-12 * g.integral());
    // no limit along phi
    const Goniogram onlyTheta = g.refined(0.05, INFINITY);
    EXPECT_EQ(onlyTheta.phi(), g.phi());
    EXPECT_TRUE(startsWith(errorOf([&] { g.refined(0, 1); }), "Goniogram::refined"));
    EXPECT_TRUE(startsWith(errorOf([&] { g.refined(0.1, NAN); }), "Goniogram::refined"));
}

// ---------------------------------------------------------------------------------------------
// Uniform sky

TEST(SkyUniform, IntegralsHaveClosedForms)
{
    const double L = 1234.5;
    const Goniogram g = uniformSky(L);
    EXPECT_EQ(g.phiCount(), 5u);
    for (std::size_t i = 0; i + 1 < g.thetaCount(); ++i)
        EXPECT_LE(g.theta()[i + 1] - g.theta()[i], kDeg * (1 + 1e-12));
    EXPECT_NEAR(g.integral(), kTwoPi * L, 1e-12 * kTwoPi * L);         // ∫ L dw = 2 pi L
    EXPECT_NEAR(g.illuminance({0, 1, 0}), M_PI * L, 1e-9 * M_PI * L);  // horizontal plane
    for (glm::dvec3 n :
         {glm::dvec3(1, 0, 0), glm::dvec3(0, 0, -1), glm::dvec3(1, 0, 1), glm::dvec3(-2, 0, 0.3)})
        EXPECT_NEAR(g.illuminance(n), M_PI * L / 2,
                    1e-6 * M_PI * L / 2);  // vertical: upper half only
    // A plane tilted beta from horizontal sees the uniform upper hemisphere:
    // E = pi L (1 + cos beta) / 2.
    for (double beta : {0.3, 1.0, 2.0, 2.9}) {
        const glm::dvec3 n(std::sin(beta) * std::sin(0.7), std::cos(beta),
                           -std::sin(beta) * std::cos(0.7));
        const double expect = M_PI * L * (1 + std::cos(beta)) / 2;
        EXPECT_NEAR(g.illuminance(n), expect, 1e-6 * expect) << "beta " << beta;
    }
    EXPECT_EQ(g.illuminance({0, -1, 0}), 0.0);
    glm::dvec3 f(0);
    for (std::size_t i = 0; i + 1 < g.thetaCount(); ++i)
        for (std::size_t j = 0; j + 1 < g.phiCount(); ++j)
            f += g.cellDirectionIntegral(i, j);
    EXPECT_NEAR(f.x, 0.0, 1e-9 * L);
    EXPECT_NEAR(f.y, M_PI * L, 1e-9 * L);
    EXPECT_NEAR(f.z, 0.0, 1e-9 * L);
}

TEST(SkyUniform, ZeroIsValidNegativeIsNot)
{
    const Goniogram dark = uniformSky(0.0);
    EXPECT_EQ(dark.integral(), 0.0);
    EXPECT_EQ(dark.illuminance({0.2, 1, 0}), 0.0);
    EXPECT_EQ(errorOf([] { uniformSky(-1, "s.gltf: extras.sky"); }),
              "s.gltf: extras.sky.luminance: must be finite and >= 0 (got -1)");
    EXPECT_TRUE(startsWith(errorOf([] { uniformSky(NAN, "s.gltf: extras.sky"); }),
                           "s.gltf: extras.sky.luminance: "));
}

// ---------------------------------------------------------------------------------------------
// User table

TEST(SkyTable, RejectsEveryMalformedTable)
{
    const std::string where = "scene.gltf: extras.sky";
    const std::vector<double> zen = {0, 30, 90}, az = {0, 90, 360};
    const std::vector<std::vector<double>> lum = {{5, 5, 5}, {1, 2, 1}, {3, 4, 3}};
    auto err = [&](std::vector<double> z, std::vector<double> a,
                   std::vector<std::vector<double>> l) {
        return errorOf([&] { tableSky(z, a, l, where); });
    };
    EXPECT_EQ(err(zen, az, lum), "(no error)");
    EXPECT_EQ(err({0, 30}, az, {{5, 5, 5}, {1, 2, 1}}),
              where + ".zenith_deg: must start at 0 and end at 90 (got 0 .. 30)");
    EXPECT_EQ(err({10, 30, 90}, az, lum),
              where + ".zenith_deg: must start at 0 and end at 90 (got 10 .. 90)");
    EXPECT_EQ(err({0, 30, 30, 90}, az, {{5, 5, 5}, {1, 2, 1}, {1, 2, 1}, {3, 4, 3}}),
              where + ".zenith_deg: must be strictly increasing (zenith_deg[2] = 30 after 30)");
    EXPECT_EQ(err({0, 60, 30, 90}, az, {{5, 5, 5}, {1, 2, 1}, {1, 2, 1}, {3, 4, 3}}),
              where + ".zenith_deg: must be strictly increasing (zenith_deg[2] = 30 after 60)");
    EXPECT_EQ(err({0}, az, {{5, 5, 5}}), where + ".zenith_deg: needs at least 2 values (got 1)");
    EXPECT_EQ(err({0, NAN, 90}, az, lum), where + ".zenith_deg[1]: not finite (nan)");
    EXPECT_EQ(err(zen, {0, 90, 350}, lum),
              where + ".azimuth_deg: must start at 0 and end at 360 (got 0 .. 350)");
    EXPECT_EQ(err(zen, {-10, 90, 360}, lum),
              where + ".azimuth_deg: must start at 0 and end at 360 (got -10 .. 360)");
    EXPECT_EQ(err(zen, {0, 400, 360}, lum),
              where + ".azimuth_deg: must be strictly increasing (azimuth_deg[2] = 360 after 400)");
    EXPECT_EQ(err(zen, az, {{5, 5, 5}, {1, 2, 1}}),
              where + ".luminance: has 2 rows, expected 3 (one per zenith_deg value)");
    EXPECT_EQ(err(zen, az, {{5, 5, 5}, {1, 2}, {3, 4, 3}}),
              where + ".luminance[1]: has 2 values, expected 3 (one per azimuth_deg value)");
    EXPECT_EQ(err(zen, az, {{5, 5, 5}, {1, -2, 1}, {3, 4, 3}}),
              where + ".luminance[1][1]: negative luminance -2");
    EXPECT_EQ(err(zen, az, {{5, 5, 5}, {1, 2, 1}, {3, NAN, 3}}),
              where + ".luminance[2][1]: not finite (nan)");
    EXPECT_EQ(err(zen, az, {{5, 5, 5}, {1, 2, 1}, {3, INFINITY, 3}}),
              where + ".luminance[2][1]: not finite (inf)");
    EXPECT_TRUE(startsWith(err(zen, az, {{5, 6, 5}, {1, 2, 1}, {3, 4, 3}}),
                           where + ".luminance[0]: zenith 0 is one direction"));
    EXPECT_TRUE(startsWith(err(zen, az, {{5, 5, 5}, {1, 2, 7}, {3, 4, 3}}),
                           where + ".luminance[1]: azimuth 0 and 360 are the same direction"));
}

TEST(SkyTable, IsTheUsersBilinearTableRefinedInTheta)
{
    // Uneven in both directions; the result is the user's table, bilinear, theta steps <= 1 deg.
    const std::vector<double> zen = {0, 7.5, 40, 90}, az = {0, 10, 200, 360};
    const std::vector<std::vector<double>> lum = {
        {50, 50, 50, 50}, {10, 20, 30, 10}, {1, 2, 3, 1}, {4, 8, 6, 4}};
    const Goniogram g = tableSky(zen, az, lum, "t");
    for (std::size_t i = 0; i + 1 < g.thetaCount(); ++i)
        EXPECT_LE(g.theta()[i + 1] - g.theta()[i], kDeg * (1 + 1e-12));
    EXPECT_EQ(g.phiCount(), 4u);
    EXPECT_EQ(g.theta().back(), kHalfPi);
    EXPECT_EQ(g.phi().back(), kTwoPi);
    for (std::size_t i = 0; i < zen.size(); ++i)
        for (std::size_t j = 0; j < az.size(); ++j)
            EXPECT_NEAR(g.eval(zen[i] * kDeg, az[j] * kDeg), lum[i][j], 1e-12 * lum[i][j])
                << i << " " << j;
    // inside the user's cell (7.5..40) x (10..200): bilinear in the user's grid
    const double s = (20 - 7.5) / (40 - 7.5), w = (100.0 - 10) / (200 - 10);
    const double expect = (1 - s) * (1 - w) * 20 + (1 - s) * w * 30 + s * (1 - w) * 2 + s * w * 3;
    EXPECT_NEAR(g.eval(20 * kDeg, 100 * kDeg), expect, 1e-12 * expect);
}

TEST(SkyTable, UniformTableIntegratesLikeTheUniformSky)
{
    const double L = 800;
    const Goniogram g = tableSky({0, 12, 90}, {0, 33, 360}, {{L, L, L}, {L, L, L}, {L, L, L}}, "t");
    EXPECT_NEAR(g.integral(), kTwoPi * L, 1e-12 * kTwoPi * L);
    EXPECT_NEAR(g.illuminance({0, 1, 0}), M_PI * L, 1e-9 * M_PI * L);
    EXPECT_NEAR(g.illuminance({0.3, 0, -1}), M_PI * L / 2, 1e-6 * M_PI * L / 2);
}

// ---------------------------------------------------------------------------------------------
// CIE standard general sky

TEST(CieSky, ParameterTable)
{
    // ISO 15469:2004 / CIE S 011/E:2003, Table 1 (spot checks of each group).
    auto is = [](int type, CieSkyType e) {
        const CieSkyType& p = cieSkyType(type);
        return p.a == e.a && p.b == e.b && p.c == e.c && p.d == e.d && p.e == e.e;
    };
    EXPECT_TRUE(is(1, {4.0, -0.70, 0, -1.0, 0}));  // CIE standard overcast sky
    EXPECT_TRUE(is(5, {0, -1, 0, -1, 0}));         // uniform
    EXPECT_TRUE(is(9, {-1, -0.55, 2, -1.5, 0.15}));
    EXPECT_TRUE(is(12, {-1, -0.32, 10, -3.0, 0.45}));  // CIE standard clear sky
    EXPECT_TRUE(is(13, {-1, -0.32, 16, -3.0, 0.30}));
    EXPECT_TRUE(is(15, {-1, -0.15, 24, -2.8, 0.15}));
    EXPECT_TRUE(contains(errorOf([] { cieSkyType(0); }), "type 0"));
    EXPECT_TRUE(contains(errorOf([] { cieSkyType(16); }), "type 16"));
}

TEST(CieSky, RelativeLuminanceIsOneAtTheZenith)
{
    for (int type = 1; type <= 15; ++type)
        for (double zs : {0.0, 0.4, 1.2, kHalfPi})
            for (double as : {0.0, 2.0, 5.5})
                for (double az : {0.0, 1.0, 4.0})
                    EXPECT_NEAR(cieRelativeLuminance(type, 0.0, az, zs, as), 1.0, 1e-13) << type;
    EXPECT_EQ(cieRelativeLuminance(12, kHalfPi + 1e-9, 0, 0.5, 0), 0.0);
}

TEST(CieSky, OvercastType1IsTheClassicOvercastSky)
{
    // Type 1 is the CIE standard overcast sky (Moon & Spencer): L(Z) / Lz =
    // (1 + 4 exp(-0.7 / cos Z)) / (1 + 4 exp(-0.7)), whatever the sun; about 1/3 at the horizon.
    for (double z : {0.0, 0.3, 0.8, 1.2, 1.5, kHalfPi})
        for (double az : {0.0, 2.0})
            for (double zs : {0.1, 1.0})
                EXPECT_NEAR(cieRelativeLuminance(1, z, az, zs, 1.0),
                            (1 + 4 * std::exp(-0.7 / std::cos(z))) / (1 + 4 * std::exp(-0.7)),
                            1e-14);
    EXPECT_NEAR(cieRelativeLuminance(1, kHalfPi, 0, 0.5, 0), 1 / (1 + 4 * std::exp(-0.7)), 1e-15);
    EXPECT_NEAR(cieRelativeLuminance(1, kHalfPi, 0, 0.5, 0), 1.0 / 3, 0.002);
    for (double z : {0.0, 0.7, kHalfPi})  // type 5 is uniform
        EXPECT_NEAR(cieRelativeLuminance(5, z, 1.0, 0.6, 3.0), 1.0, 1e-14);
}

TEST(CieSky, Type12IsTheCieClearSky)
{
    // The CIE clear sky of 1973 (CIE 22, Kittler): L / Lz =
    // (0.91 + 10 exp(-3 chi) + 0.45 cos^2 chi)(1 - exp(-0.32 / cos Z)) /
    // ((0.91 + 10 exp(-3 Zs) + 0.45 cos^2 Zs)(1 - exp(-0.32))); 1 - 10 exp(-3 pi / 2) = 0.9102.
    auto clear = [](double z, double az, double zs, double as) {
        const double chi = std::acos(
            std::clamp(std::cos(zs) * std::cos(z) + std::sin(zs) * std::sin(z) * std::cos(az - as),
                       -1.0, 1.0));
        auto f = [](double x) {
            return 0.91 + 10 * std::exp(-3 * x) + 0.45 * std::cos(x) * std::cos(x);
        };
        return f(chi) * (1 - std::exp(-0.32 / std::cos(z))) / (f(zs) * (1 - std::exp(-0.32)));
    };
    for (double z : {0.2, 0.7, 1.1, 1.5})
        for (double az : {0.0, 1.0, 3.0, 5.0})
            for (double zs : {0.3, 0.9, 1.4}) {
                const double expect = clear(z, az, zs, 0.8);
                EXPECT_NEAR(cieRelativeLuminance(12, z, az, zs, 0.8), expect, 3e-4 * expect);
            }
}

// The sun positions of the interpolation checks: altitude 0 and 90, azimuth at and near 0/360.
struct SunCase {
    double altitudeDeg, azimuthDeg;
};
const SunCase kSuns[] = {{0, 359.995}, {90, 0}, {27, 0.003}, {64, 222}};

// Max relative error of the goniogram against the formula over random directions, random
// directions within 4 degrees of the sun, and random directions within 2 degrees of the horizon.
double maxRelativeError(const Goniogram& g, int type, double lz, const SunCase& s,
                        std::mt19937& rng)
{
    const double zs = (90 - s.altitudeDeg) * kDeg, as = s.azimuthDeg * kDeg;
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double worst = 0;
    auto check = [&](double t, double p) {
        const double exact = lz * cieRelativeLuminance(type, t, p, zs, as);
        worst = std::max(worst, std::abs(g.eval(t, p) - exact) / exact);
    };
    for (int k = 0; k < 12000; ++k)  // uniform on the hemisphere
        check(std::acos(u(rng)), kTwoPi * u(rng));
    for (int k = 0; k < 6000; ++k) {  // around the sun
        const double t = std::clamp(zs + 4 * kDeg * (2 * u(rng) - 1), 0.0, kHalfPi);
        const double p = as + 4 * kDeg * (2 * u(rng) - 1) / std::max(std::sin(zs), 0.05);
        check(t, p);
    }
    for (int k = 0; k < 4000; ++k)  // where the clear types' gradation bends
        check(kHalfPi - 2 * kDeg * u(rng), kTwoPi * u(rng));
    check(zs, as);  // the sun itself is a node
    return worst;
}

TEST(CieSky, InterpolationErrorBelowATenthOfAPercent)
{
    std::mt19937 rng(13);
    std::size_t maxCells = 0;
    for (int type = 1; type <= 15; ++type) {
        double worstType = 0;
        for (const SunCase& s : kSuns) {
            const double lz = 7000;
            const Goniogram g = cieSky(type, lz, s.altitudeDeg, s.azimuthDeg);
            const std::size_t cells = (g.thetaCount() - 1) * (g.phiCount() - 1);
            maxCells = std::max(maxCells, cells);
            EXPECT_LT(cells, 150000u);
            for (std::size_t i = 0; i + 1 < g.thetaCount(); ++i)
                ASSERT_LE(g.theta()[i + 1] - g.theta()[i], kDeg * (1 + 1e-9));
            const double worst = maxRelativeError(g, type, lz, s, rng);
            worstType = std::max(worstType, worst);
            EXPECT_LT(worst, 1e-3)
                << "type " << type << ", sun " << s.altitudeDeg << " / " << s.azimuthDeg;
        }
        std::printf("[          ] CIE type %2d: max interpolation error %.4f %%\n", type,
                    100 * worstType);
    }
    std::printf("[          ] largest grid: %zu cells\n", maxCells);
}

TEST(CieSky, HorizontalIlluminanceMatchesQuadratureOfTheFormula)
{
    struct Case {
        int type;
        SunCase sun;
    };
    for (const Case& c : {Case{15, {35, 100}}, Case{8, {5, 359.995}}, Case{3, {60, 10}}}) {
        const double lz = 5000;
        const double zs = (90 - c.sun.altitudeDeg) * kDeg, as = c.sun.azimuthDeg * kDeg;
        const Goniogram g = cieSky(c.type, lz, c.sun.altitudeDeg, c.sun.azimuthDeg);
        // Midpoint rule on the formula: the cusp at the sun only costs it ~1e-5 at this size.
        const int nt = 500, np = 1000;
        double quad = 0;
        for (int a = 0; a < nt; ++a) {
            const double t = kHalfPi * (a + 0.5) / nt;
            for (int b = 0; b < np; ++b)
                quad += cieRelativeLuminance(c.type, t, kTwoPi * (b + 0.5) / np, zs, as) *
                        std::cos(t) * std::sin(t);
        }
        quad *= lz * (kHalfPi / nt) * (kTwoPi / np);
        EXPECT_NEAR(g.illuminance({0, 1, 0}), quad, 1e-3 * quad) << "type " << c.type;
        std::printf("[          ] type %2d, sun %g / %g: E_h %.6g lx, quadrature %.6g lx (%.2e)\n",
                    c.type, c.sun.altitudeDeg, c.sun.azimuthDeg, g.illuminance({0, 1, 0}), quad,
                    g.illuminance({0, 1, 0}) / quad - 1);
    }
}

TEST(CieSky, SymmetricAboutTheSunsAzimuth)
{
    std::mt19937 rng(14);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int type : {2, 11, 15}) {
        const double alt = 38, az = 17;  // the mirror of phi = 0 is 34 deg: the grid must carry it
        const Goniogram g = cieSky(type, 1, alt, az);
        const double zs = (90 - alt) * kDeg, as = az * kDeg;
        for (int k = 0; k < 3000; ++k) {
            const double t = kHalfPi * u(rng), d = M_PI * u(rng);
            const double l = cieRelativeLuminance(type, t, as + d, zs, as);
            EXPECT_NEAR(cieRelativeLuminance(type, t, as - d, zs, as), l, 1e-12 * l);
            EXPECT_NEAR(g.eval(t, as - d), g.eval(t, as + d), 1e-9 * l);
        }
        // vertical planes mirrored about the sun's vertical plane
        for (double off : {0.3, 1.2, 2.5}) {
            const double e1 = g.illuminance(skyDirection(kHalfPi, as + off));
            const double e2 = g.illuminance(skyDirection(kHalfPi, as - off));
            EXPECT_NEAR(e1, e2, 1e-6 * e1);
        }
        // the sun side is the bright side: east sun, east facade
        EXPECT_GT(g.illuminance(skyDirection(kHalfPi, as)),
                  g.illuminance(skyDirection(kHalfPi, as + M_PI)));
    }
}

TEST(CieSky, ArgumentsAreCheckedAndWrapped)
{
    const std::string w = "scene.gltf: extras.sky";
    EXPECT_EQ(errorOf([&] { cieSky(0, 1, 30, 0, w); }),
              w + ".cie_type: must be an integer 1..15 (got 0)");
    EXPECT_EQ(errorOf([&] { cieSky(16, 1, 30, 0, w); }),
              w + ".cie_type: must be an integer 1..15 (got 16)");
    EXPECT_TRUE(startsWith(errorOf([&] { cieSky(3, -1, 30, 0, w); }), w + ".zenith_luminance: "));
    EXPECT_TRUE(startsWith(errorOf([&] { cieSky(3, NAN, 30, 0, w); }), w + ".zenith_luminance: "));
    EXPECT_TRUE(startsWith(errorOf([&] { cieSky(3, 1, -0.1, 0, w); }), w + ".sun_altitude_deg: "));
    EXPECT_TRUE(startsWith(errorOf([&] { cieSky(3, 1, 90.5, 0, w); }), w + ".sun_altitude_deg: "));
    EXPECT_TRUE(startsWith(errorOf([&] { cieSky(3, 1, NAN, 0, w); }), w + ".sun_altitude_deg: "));
    EXPECT_TRUE(
        startsWith(errorOf([&] { cieSky(3, 1, 30, INFINITY, w); }), w + ".sun_azimuth_deg: "));

    const Goniogram dark = cieSky(12, 0, 30, 0);  // zenith luminance 0 is valid
    EXPECT_EQ(dark.integral(), 0.0);

    const Goniogram a = cieSky(12, 1, 30, -90), b = cieSky(12, 1, 30, 270),
                    c = cieSky(12, 1, 30, 630);
    EXPECT_EQ(a.phi(), b.phi());
    EXPECT_EQ(a.values(), b.values());
    EXPECT_EQ(c.values(), b.values());
    // west sun: the west facade is the bright one
    EXPECT_GT(a.illuminance({-1, 0, 0}), a.illuminance({1, 0, 0}));
}

TEST(CieSky, GridsStaySmallAndBuildFast)
{
    // Azimuthally uniform types need no phi resolution at all; the sun at the zenith neither.
    for (int type : {1, 3, 5})
        EXPECT_EQ(cieSky(type, 1, 40, 10).phiCount(), 5u);
    EXPECT_EQ(cieSky(15, 1, 90, 10).phiCount(), 5u);
    const auto t0 = std::chrono::steady_clock::now();
    std::size_t cells = 0;
    for (int type = 1; type <= 15; ++type) {
        const Goniogram g = cieSky(type, 1, 3, 47);  // a low sun: the largest grids
        cells = std::max(cells, (g.thetaCount() - 1) * (g.phiCount() - 1));
    }
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_LT(cells, 150000u);
    std::printf("[          ] sun at 3 deg: largest grid %zu cells; 15 types built in %.0f ms\n",
                cells, ms);
}


// ---------------------------------------------------------------------------------------------
// The device's node search (host/sky/sky_tables.h appendSkySearch, kernels/lib/sky.h)

// The binary search over [lo, hi) of lib/sky.h sky_node_search: the largest i in it with
// nodes[i] <= x.
std::uint32_t searchBetween(const std::vector<float>& axis, float x, std::uint32_t lo, std::uint32_t hi)
{
    while (hi - lo > 1) {
        const std::uint32_t mid = (lo + hi) >> 1;
        if (axis[mid] <= x)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

// sky_node_search, step for step in float: x's bucket, then the search inside its bounds.
std::uint32_t bucketedSearch(const std::vector<float>& axis, std::uint32_t n, float x)
{
    const float* search = axis.data() + n;
    std::uint32_t buckets, lo, hi;
    std::memcpy(&buckets, &search[FEN_SKY_SEARCH_BUCKETS], 4);
    const float f = x * search[FEN_SKY_SEARCH_SCALE];
    const std::uint32_t b =
        f > 0.0f ? std::min(static_cast<std::uint32_t>(std::fmin(f, static_cast<float>(buckets))), buckets - 1) : 0;
    std::memcpy(&lo, &search[FEN_SKY_SEARCH_HINTS + 2 * b], 4);
    std::memcpy(&hi, &search[FEN_SKY_SEARCH_HINTS + 2 * b + 1], 4);
    return searchBetween(axis, x, lo, hi);
}

// The full search it stands for: the largest i < n - 1 with nodes[i] <= x.
std::uint32_t fullSearch(const std::vector<float>& axis, std::uint32_t n, float x)
{
    return searchBetween(axis, x, 0, n - 1);
}

TEST(SkySearch, EveryBucketHoldsTheFullSearchsAnswer)
{
    // Even steps; nodes crowded around a sun (steps of 2e-5 rad beside steps of a degree); the
    // ground's doubled pi/2; a CIE sky's own nodes on both axes.
    std::vector<std::vector<double>> axes;
    std::vector<double> even, crowded = {0.0}, ground;
    for (int i = 0; i <= 90; ++i)
        even.push_back(i == 90 ? kHalfPi : i * kDeg);
    for (double t = kDeg; t < 0.7; t += kDeg)
        crowded.push_back(t);
    for (int i = 0; i < 400; ++i)
        crowded.push_back(0.7 + 2e-5 * i);
    crowded.push_back(kHalfPi);
    for (int i = 0; i <= 10; ++i)
        ground.push_back(i * kHalfPi / 10);
    for (int i = 0; i <= 10; ++i)
        ground.push_back(kHalfPi + i * kHalfPi / 10);
    const Goniogram cie = cieSky(12, 3500.0, 35.0, 200.0);
    axes = {even, crowded, ground, cie.theta(), cie.phi()};
    std::mt19937 rng(3);
    for (std::size_t a = 0; a < axes.size(); ++a) {
        std::vector<float> axis;
        for (double v : axes[a])
            axis.push_back(static_cast<float>(v));
        const auto n = static_cast<std::uint32_t>(axis.size());
        appendSkySearch(axis);
        ASSERT_EQ(axis.size(), n + FEN_SKY_SEARCH_HINTS + 2 * 4 * n) << "axis " << a;
        // every node and its float neighbours, every bucket edge and its neighbours, random
        // points, and the ends and beyond them
        std::vector<float> xs = {-1.0f, 0.0f, axis[n - 1], 2 * axis[n - 1], NAN, INFINITY};
        for (std::uint32_t i = 0; i < n; ++i)
            xs.insert(xs.end(), {axis[i], std::nextafter(axis[i], -1.0f), std::nextafter(axis[i], 10.0f)});
        const float scale = axis[n + FEN_SKY_SEARCH_SCALE];
        for (std::uint32_t b = 0; b <= 4 * n; ++b) {
            const float e = static_cast<float>(b / static_cast<double>(scale));
            xs.insert(xs.end(), {e, std::nextafter(e, -1.0f), std::nextafter(e, 10.0f)});
        }
        std::uniform_real_distribution<float> u(0.0f, axis[n - 1]);
        for (int k = 0; k < 20000; ++k)
            xs.push_back(u(rng));
        std::size_t checked = 0;
        for (float x : xs) {
            ASSERT_EQ(bucketedSearch(axis, n, x), fullSearch(axis, n, x)) << "axis " << a << ", x = " << x;
            ++checked;
        }
        EXPECT_GT(checked, 20000u);
    }
    // The doubled horizon node: x = pi/2 reads the ground's row (the second of the two), as the
    // full search does.
    std::vector<float> g;
    for (double v : ground)
        g.push_back(static_cast<float>(v));
    appendSkySearch(g);
    EXPECT_EQ(bucketedSearch(g, 22, static_cast<float>(kHalfPi)), 11u);
    // Axes the search cannot take.
    std::vector<float> one = {0.0f};
    EXPECT_TRUE(contains(errorOf([&] { appendSkySearch(one); }), "an axis of 1 nodes"));
}

}  // namespace
}  // namespace fen
