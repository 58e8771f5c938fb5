// opening_aim_test.cpp — the opening aim (DESIGN.md §3.5) against what it claims:
//  - findOpenings() joins glass triangles into panes where they share a corner and a plane, and
//    only there, and knows which of a pane's triangles face against it;
//  - the device's mixture draws directions with the density it divides by: chi-square against a
//    CPU oracle of that density (p > 1e-3, fixed seed), the factor it returns equal to the oracle's,
//    and E[(cos/pi) / p] = 1 over the hemisphere within 4 sigma (the estimator's unbiasedness);
//  - a path crossing an opening takes the pane's side, whichever way its triangle winds, and adds
//    itself to that side's statistics; other glass is "other";
//  - learn() turns written statistics into the documented weights and gates, puts each triangle's
//    side weights the right way round, and a checkpoint carries them.
// Unbiasedness of whole renders with the aim on: Renders/AimedOpenings.*.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "cl/launch.h"
#include "io/state_io.h"
#include "scatter/opening_aim.h"
#include "scene/scene.h"
#include "shared/fen_render.h"
#include "support/cl_fixture.h"
#include "support/statistics.h"

namespace fen {
namespace {

constexpr double kPi = 3.14159265358979323846;

Triangle tri(glm::vec3 a, glm::vec3 b, glm::vec3 c) { return {a, b, c}; }

// A scene of glass and one wall: pane A (two triangles, z = -3, the second wound against the
// first), pane B (two triangles, x = 2, sharing an edge with nothing), pane C (one triangle at
// right angles to A, sharing A's corner (1, 0.5, -3)), a diffuse wall touching A, and a glass
// triangle of zero area.
Scene glassScene()
{
    Scene s;
    Material wall;
    wall.name = "wall";
    Material glass;
    glass.name = "glass";
    glass.glass = true;
    glass.transmission = glm::vec3(0.9f);
    s.materials = {wall, glass};
    const glm::vec3 a0(-1, 0.5f, -3), a1(1, 0.5f, -3), a2(1, 2, -3), a3(-1, 2, -3);
    s.triangles = {
        tri(a0, a1, a2),                                   // 0: A, normal +z
        tri(a0, a3, a2),                                   // 1: A, normal -z (wound against)
        tri({2, 0, -1}, {2, 0, 1}, {2, 1, 0}),             // 2: B, normal -x
        tri({2, 0, 1}, {2, 1, 1}, {2, 1, 0}),              // 3: B
        tri(a1, {1, 0.5f, -4}, {1, 2, -4}),                // 4: C, x = 1
        tri(a0, a1, {0, 0, -3.5f}),                        // 5: the wall, diffuse
        tri({5, 5, 5}, {6, 6, 6}, {7, 7, 7}),              // 6: glass of zero area
    };
    s.triangleMaterial = {1, 1, 1, 1, 1, 0, 1};
    return s;
}

TEST(OpeningAim, OpeningsArePanesOfGlassThatShareACornerAndAPlane)
{
    const Scene s = glassScene();
    const std::vector<Opening> o = findOpenings(s);
    ASSERT_EQ(o.size(), 3u);
    // largest first: A (3 m^2), B (1 + 0.5), C (0.75)
    EXPECT_EQ(o[0].triangles, (std::vector<std::uint32_t>{0, 1}));
    EXPECT_NEAR(o[0].area_m2, 3.0, 1e-6);
    EXPECT_EQ(o[0].flipped, (std::vector<char>{0, 1}));
    EXPECT_EQ(o[1].triangles, (std::vector<std::uint32_t>{2, 3}));
    EXPECT_NEAR(o[1].area_m2, 1.0 + 0.5, 1e-6);
    EXPECT_EQ(o[2].triangles, (std::vector<std::uint32_t>{4}));
    EXPECT_NEAR(o[2].area_m2, 0.75, 1e-6);
    EXPECT_NEAR(o[0].normal.z, 1.0, 1e-12);
}

// The mixture's density over the cosine's, in double: what the device claims.
struct HostAim {
    const dev::OpeningAim& a;
    glm::dvec3 x, n;
    std::vector<double> w;
    double total = 0.0;
    HostAim(const dev::OpeningAim& aim, glm::dvec3 x_, glm::dvec3 n_) : a(aim), x(x_), n(n_)
    {
        for (std::uint32_t i = 0; i < a.triangles; ++i) {
            const auto& t = a.tri[i];
            const glm::dvec3 p0(t.p0.x, t.p0.y, t.p0.z), e1(t.e1.x, t.e1.y, t.e1.z), e2(t.e2.x, t.e2.y, t.e2.z);
            const glm::dvec3 nt(t.normal.x, t.normal.y, t.normal.z);
            const double h = glm::dot(x - p0, nt);
            const double sw = h > 0 ? t.e1.w : (h < 0 ? t.e2.w : 0.0);
            const glm::dvec3 d = p0 + (e1 + e2) / 3.0 - x;
            const double d2 = glm::dot(d, d);
            w.push_back(sw > 0 && glm::dot(n, d) > 0 ? sw * t.p0.w * std::abs(h) / (d2 * std::sqrt(d2)) : 0.0);
            total += w.back();
        }
    }
    double ratio(glm::dvec3 v) const
    {
        const double c = glm::dot(v, n);
        if (c <= 0)
            return 0.0;
        double p = 0.0;
        for (std::uint32_t i = 0; i < a.triangles; ++i) {
            if (!(w[i] > 0))
                continue;
            const auto& t = a.tri[i];
            const glm::dvec3 p0(t.p0.x, t.p0.y, t.p0.z), e1(t.e1.x, t.e1.y, t.e1.z), e2(t.e2.x, t.e2.y, t.e2.z);
            const glm::dvec3 pv = glm::cross(v, e2);
            const double det = glm::dot(e1, pv);
            if (det == 0)
                continue;
            const glm::dvec3 tv = x - p0, qv = glm::cross(tv, e1);
            const double u = glm::dot(tv, pv) / det, b = glm::dot(v, qv) / det, s = glm::dot(e2, qv) / det;
            if (u >= 0 && b >= 0 && u + b <= 1 && s > 0)
                p += (w[i] / total) * s * s / (t.p0.w * std::abs(glm::dot(v, glm::dvec3(t.normal.x, t.normal.y, t.normal.z))));
        }
        const double sh = a.cosine_share, pc = c / kPi;
        return (sh * pc + (1 - sh) * p) / pc;
    }
};

dev::AimTriangle aimTriangle(const Triangle& t, float front, float back)
{
    const glm::vec3 e1 = t.p1 - t.p0, e2 = t.p2 - t.p0, c = glm::cross(e1, e2), n = glm::normalize(c);
    dev::AimTriangle a{};
    a.p0 = {t.p0.x, t.p0.y, t.p0.z, 0.5f * glm::length(c)};
    a.e1 = {e1.x, e1.y, e1.z, front};
    a.e2 = {e2.x, e2.y, e2.z, back};
    a.normal = {n.x, n.y, n.z, 0.0f};
    return a;
}

TEST(OpeningAim, TheDeviceMixtureDrawsTheDensityItDividesBy)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const Scene s = glassScene();
    dev::OpeningAim aim{};
    aim.cosine_share = 0.5f;
    // pane A seen from its front, weight 1; pane B, weight 3, partly below the floor (its lower
    // edge at y = 0, and a triangle reaching below it); a triangle seen from its back, whose back
    // weight is 0 (never aimed at)
    aim.tri[0] = aimTriangle(s.triangles[0], 1.0f, 0.0f);
    aim.tri[1] = aimTriangle(tri({-1, 0.5f, -3}, {1, 2, -3}, {-1, 2, -3}), 1.0f, 0.0f);
    aim.tri[2] = aimTriangle(tri({2, -0.5f, -1}, {2, -0.5f, 1}, {2, 2, 0}), 3.0f, 0.0f);
    aim.tri[3] = aimTriangle(tri({-1, 0, 3}, {1, 0, 3}, {1, 2, 3}), 5.0f, 0.0f);  // normal +z: x sees its back
    aim.triangles = 4;
    const glm::dvec3 x(0.0, 0.0, 0.0), n(0.0, 1.0, 0.0);
    const HostAim host(aim, x, n);
    ASSERT_GT(host.w[0], 0.0);
    ASSERT_GT(host.w[2], 0.0);

    const std::uint32_t count = 1u << 20;
    cl::Buffer aimBuf = ctx->buffer(CL_MEM_READ_ONLY, sizeof aim, "aim", &aim);
    cl::Buffer out = ctx->buffer(CL_MEM_WRITE_ONLY, std::size_t{count} * 16, "draws");
    cl::Buffer totalBuf = ctx->buffer(CL_MEM_WRITE_ONLY, 4, "total");
    cl::Kernel k(ctx->program("test_opening_probes.cl"), "aim_mixture_probe");
    const cl_float4 xf = {{0.0f, 0.0f, 0.0f, 0.0f}}, nf = {{0.0f, 1.0f, 0.0f, 0.0f}};
    ocl::setKernelArgs(k, aimBuf, xf, nf, std::uint32_t{23}, count, out, totalBuf);
    ocl::launch(*ctx, k, "aim_mixture_probe", count);
    std::vector<cl_float4> v(count);
    ctx->queue().enqueueReadBuffer(out, CL_TRUE, 0, std::size_t{count} * 16, v.data());
    float total = 0.0f;
    ctx->queue().enqueueReadBuffer(totalBuf, CL_TRUE, 0, 4, &total);
    EXPECT_NEAR(total, host.total, 1e-5 * host.total);

    // bins over the cosine's square (u1 = r^2, u2 = azimuth / 2 pi in the basis (x, z)), plus one
    // for directions below the surface
    const int B = 24, sub = 64;
    std::vector<double> observed(B * B + 1, 0.0), expected(B * B + 1, 0.0);
    std::size_t agree = 0, drawn = 0;
    double sumInv = 0.0, sumInv2 = 0.0;
    for (const cl_float4& d : v) {
        const glm::dvec3 dir(d.s[0], d.s[1], d.s[2]);
        const double ratio = d.s[3];
        if (!(ratio > 0.0)) {
            observed[B * B] += 1;
            EXPECT_LE(dir.y, 1e-6);
            continue;
        }
        ++drawn;
        const double hr = host.ratio(glm::normalize(dir));
        agree += std::abs(hr - ratio) <= 1e-3 * hr;
        sumInv += 1.0 / ratio;
        sumInv2 += 1.0 / (ratio * ratio);
        const double u1 = std::min(dir.x * dir.x + dir.z * dir.z, 1.0 - 1e-12);
        double u2 = std::atan2(dir.z, dir.x) / (2 * kPi);
        u2 = u2 < 0 ? u2 + 1 : u2;
        const int i = std::min(static_cast<int>(u1 * B), B - 1), j = std::min(static_cast<int>(u2 * B), B - 1);
        observed[static_cast<std::size_t>(i * B + j)] += 1;
    }
    // the density p integrates to ratio over the square (the cosine's square is its
    // equal-probability map): each bin's integral by a 64 x 64 midpoint rule over (cos, u2) --
    // du1 = 2 cos dcos, which takes the 1 / cos of the triangles' part at the horizon out of the
    // integrand
    double inside = 0.0;
    for (int i = 0; i < B; ++i) {
        const double cHi = std::sqrt(1.0 - static_cast<double>(i) / B), cLo = std::sqrt(1.0 - (i + 1.0) / B);
        for (int j = 0; j < B; ++j) {
            double acc = 0.0;
            for (int a = 0; a < sub; ++a)
                for (int b = 0; b < sub; ++b) {
                    const double c = cLo + (a + 0.5) / sub * (cHi - cLo), u2 = (j + (b + 0.5) / sub) / B;
                    const double r = std::sqrt(1.0 - c * c), phi = 2 * kPi * u2;
                    acc += host.ratio({r * std::cos(phi), c, r * std::sin(phi)}) * 2.0 * c * (cHi - cLo);
                }
            expected[static_cast<std::size_t>(i * B + j)] = acc / (sub * sub) / B * count;
            inside += expected[static_cast<std::size_t>(i * B + j)];
        }
    }
    expected[B * B] = count - inside;
    ASSERT_GT(expected[B * B], 100.0);  // the test does reach below the surface
    const double pv = test::chiSquarePValue(observed, expected);
    std::printf("[ aim ] %u draws, %.0f below the surface (expected %.0f): chi-square p = %.3g\n", count,
                observed[B * B], expected[B * B], pv);
    EXPECT_GT(pv, 1e-3);
    // the factor the weight is divided by, the oracle's (but at the triangles' edges)
    EXPECT_GE(static_cast<double>(agree), 0.999 * static_cast<double>(drawn));
    // E[(cos/pi) / p] over the hemisphere = 1: within 4 sigma of the mean's standard error
    const double mean = sumInv / count;
    const double se = std::sqrt((sumInv2 / count - mean * mean) / count);
    std::printf("[ aim ] E[(cos/pi)/p] = %.5f +- %.5f\n", mean, se);
    EXPECT_NEAR(mean, 1.0, 4.0 * se);
}

TEST(OpeningAim, APathTakesThePanesSideAndCountsThere)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const Scene s = glassScene();
    OpeningAim aim(*ctx, OpeningAimOptions{}, &s);
    ASSERT_EQ(aim.openings().size(), 3u);
    // triangle 0 (A, +z) and 1 (A, wound against) crossed going -z: both enter A from its front,
    // side 0 (code 1); triangle 1 going +z: side 1 (code 2); triangle 2 (B, opening 1, normal -x)
    // going +x comes from its front: side 0 (code 3); the zero-area glass: other (255); and a path
    // that has not bounced yet, straight from the sky, through A: other, not counted
    const std::vector<std::uint32_t> prim = {0, 1, 1, 2, 6, 0};
    const std::vector<cl_float4> dir = {{{0, 0, -1, 0}}, {{0, 0, -1, 0}}, {{0, 0, 1, 0}}, {{1, 0, 0, 0}}, {{0, 1, 0, 0}},
                                        {{0, 0, -1, 0}}};
    const std::vector<std::uint32_t> bounced = {1, 1, 1, 1, 1, 0};
    std::vector<cl_float4> ng;
    for (std::uint32_t p : prim) {
        const Triangle& t = s.triangles[p];
        const glm::vec3 c = glm::cross(t.p1 - t.p0, t.p2 - t.p0);
        const glm::vec3 nn = glm::length(c) > 0 ? glm::normalize(c) : glm::vec3(0, 0, 1);
        ng.push_back({{nn.x, nn.y, nn.z, 0}});
    }
    const auto n = static_cast<std::uint32_t>(prim.size());
    cl::Buffer primBuf = ctx->buffer(CL_MEM_READ_ONLY, n * 4, "prims", prim.data());
    cl::Buffer dirBuf = ctx->buffer(CL_MEM_READ_ONLY, n * 16, "dirs", dir.data());
    cl::Buffer ngBuf = ctx->buffer(CL_MEM_READ_ONLY, n * 16, "normals", ng.data());
    cl::Buffer bouncedBuf = ctx->buffer(CL_MEM_READ_ONLY, n * 4, "bounced", bounced.data());
    cl::Buffer codeBuf = ctx->buffer(CL_MEM_WRITE_ONLY, n * 4, "codes");
    cl::Kernel k(ctx->program("test_opening_probes.cl"), "opening_enter_probe");
    ocl::setKernelArgs(k, aim.aim(), aim.prims(), aim.stats(), primBuf, dirBuf, ngBuf, bouncedBuf, n, codeBuf);
    ocl::launch(*ctx, k, "opening_enter_probe", n);
    std::vector<std::uint32_t> code(n);
    ctx->queue().enqueueReadBuffer(codeBuf, CL_TRUE, 0, n * 4, code.data());
    EXPECT_EQ(code, (std::vector<std::uint32_t>{1, 1, 2, 3, FEN_PATH_OPENING_OTHER, FEN_PATH_OPENING_OTHER}));
    std::vector<std::uint64_t> words(6 * FEN_OPENING_STATS_WORDS);
    ctx->queue().enqueueReadBuffer(aim.stats(), CL_TRUE, 0, words.size() * 8, words.data());
    EXPECT_EQ(words[0 * FEN_OPENING_STATS_WORDS + FEN_OPENING_ENTRIES], 2u);  // A, side 0
    EXPECT_EQ(words[1 * FEN_OPENING_STATS_WORDS + FEN_OPENING_ENTRIES], 1u);  // A, side 1
    EXPECT_EQ(words[2 * FEN_OPENING_STATS_WORDS + FEN_OPENING_ENTRIES], 1u);  // B, side 0
    EXPECT_EQ(words[0 * FEN_OPENING_STATS_WORDS + FEN_OPENING_ENTERED_LO], 2u); // weight 1 at units 1
}

// Writes one pass's statistics: per opening side (delivered, entered, entries).
void writeStats(ocl::Context& ctx, const OpeningAim& aim, const std::vector<std::array<double, 3>>& sides)
{
    std::vector<std::uint64_t> words(sides.size() * FEN_OPENING_STATS_WORDS, 0);
    for (std::size_t i = 0; i < sides.size(); ++i) {
        words[i * FEN_OPENING_STATS_WORDS + FEN_OPENING_DELIVERED_LO] = static_cast<std::uint64_t>(sides[i][0]);
        words[i * FEN_OPENING_STATS_WORDS + FEN_OPENING_ENTERED_LO] = static_cast<std::uint64_t>(sides[i][1]);
        words[i * FEN_OPENING_STATS_WORDS + FEN_OPENING_ENTRIES] = static_cast<std::uint64_t>(sides[i][2]);
    }
    ctx.queue().enqueueWriteBuffer(aim.stats(), CL_TRUE, 0, words.size() * 8, words.data());
}

TEST(OpeningAim, LearnsWhatAUnitEnteringBringsAndACheckpointCarriesIt)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const Scene s = glassScene();
    OpeningAimOptions o;
    o.minEntries = 64;
    o.minShare = 0.01;
    OpeningAim aim(*ctx, o, &s);
    EXPECT_EQ(aim.aimedTriangles(), 0u);  // nothing learned: nothing aimed at
    // A side 0: ratio 4000 / 1000 = 4 (area 3: 12); A side 1: 100 entries, nothing delivered;
    // B side 1: ratio 2 (area 1.5: 3); C side 0: ratio 100 but 10 entries (under the gate);
    // C side 1: ratio 0.1 (area 0.75: 0.075 < 1 % of 12)
    writeStats(*ctx, aim, {{4000, 1000, 500}, {0, 500, 100}, {0, 0, 0}, {2000, 1000, 200}, {1000, 10, 10}, {100, 1000, 100}});
    aim.learn();
    EXPECT_DOUBLE_EQ(aim.weight(0, 0), 1.0);
    EXPECT_DOUBLE_EQ(aim.weight(0, 1), 0.0);
    EXPECT_DOUBLE_EQ(aim.weight(1, 1), 0.5);
    EXPECT_DOUBLE_EQ(aim.weight(1, 0), 0.0);
    EXPECT_DOUBLE_EQ(aim.weight(2, 0), 0.0);
    EXPECT_DOUBLE_EQ(aim.weight(2, 1), 0.0);
    const dev::OpeningAim& d = aim.deviceAim();
    ASSERT_EQ(d.triangles, 4u);  // A's two, then B's two
    EXPECT_FLOAT_EQ(d.tri[0].e1.w, 1.0f);  // triangle 0 faces A's way: front = side 0
    EXPECT_FLOAT_EQ(d.tri[0].e2.w, 0.0f);
    EXPECT_FLOAT_EQ(d.tri[1].e1.w, 0.0f);  // triangle 1 wound against: its front is A's side 1
    EXPECT_FLOAT_EQ(d.tri[1].e2.w, 1.0f);
    EXPECT_FLOAT_EQ(d.tri[2].e2.w, 0.5f);  // B's side 1, behind its triangles' normal
    EXPECT_NEAR(d.tri[0].p0.w, 1.5f, 1e-6f);

    // a second pass adds to the totals: C side 0 passes the gate (ratio (1000 + 6000) / (10 + 60))
    writeStats(*ctx, aim, {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {6000, 60, 60}, {0, 0, 0}});
    aim.learn();
    EXPECT_DOUBLE_EQ(aim.weight(2, 0), 1.0);
    EXPECT_DOUBLE_EQ(aim.weight(0, 0), 0.04);
    EXPECT_EQ(aim.deviceAim().triangles, 5u);

    StateWriter w;
    aim.save(w);
    OpeningAim resumed(*ctx, o, &s);
    StateReader r(w.bytes(), "test checkpoint");
    resumed.load(r);
    r.end();
    EXPECT_EQ(std::memcmp(&resumed.deviceAim(), &aim.deviceAim(), sizeof(dev::OpeningAim)), 0);

    // a checkpoint of another scene's openings is an error naming the field
    StateWriter other;
    other.f64s("aim.totals", {1.0, 2.0});
    other.u64("aim.passes", 1);
    StateReader bad(other.bytes(), "other.ckpt");
    try {
        resumed.load(bad);
        ADD_FAILURE() << "loaded another scene's totals";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("aim.totals"), std::string::npos) << e.what();
    }
}

// The share that minimises A / (1 - s) + B / s.
float bestShare(double a, double b)
{
    return static_cast<float>(std::sqrt(b) / (std::sqrt(a) + std::sqrt(b)));
}

// The cosine's share at a path's first vertex, learned: each pass's sums of squares times the share
// that drew them estimate A (the aim's region, as if aimed) and B (the rest, as if drawn from the
// cosine); the share is the one that minimises A / (1 - s) + B / s, within its bounds; the share
// past the first vertex stays; a checkpoint carries A and B.
TEST(OpeningAim, LearnsTheShareThatMinimisesTheSecondMomentAndACheckpointCarriesIt)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const Scene s = glassScene();
    OpeningAimOptions o;
    o.learnShare = true;
    OpeningAim aim(*ctx, o, &s);
    EXPECT_FLOAT_EQ(aim.firstShare(), 0.75f) << "where it starts";
    aim.learnShare(0.0, 0.0);  // nothing drawn by the mixture: nothing learned
    EXPECT_FLOAT_EQ(aim.firstShare(), 0.75f);
    // pass 1 at 0.75: 600 of 1000 in the aim's region: A = 600 x 0.25, B = 400 x 0.75
    aim.learnShare(1000.0, 600.0);
    const float s1 = bestShare(150.0, 300.0);
    EXPECT_EQ(aim.firstShare(), s1);
    // pass 2, drawn at s1
    aim.learnShare(1000.0, 600.0);
    const double a2 = 150.0 + 600.0 * (1.0 - s1), b2 = 300.0 + 400.0 * static_cast<double>(s1);
    EXPECT_EQ(aim.firstShare(), bestShare(a2, b2));
    aim.learn();  // uploads it
    dev::OpeningAim d;
    ctx->queue().enqueueReadBuffer(aim.aim(), CL_TRUE, 0, sizeof d, &d);
    EXPECT_EQ(d.first_share, bestShare(a2, b2));
    EXPECT_FLOAT_EQ(d.cosine_share, 0.75f) << "past the first vertex the share stays";
    EXPECT_EQ(aim.report()["first_share"].get<float>(), bestShare(a2, b2));
    // A checkpoint carries A and B: the same share after loading
    StateWriter w;
    aim.save(w);
    OpeningAim again(*ctx, o, &s);
    StateReader r(w.bytes(), "test.ckpt");
    again.load(r);
    EXPECT_EQ(again.firstShare(), bestShare(a2, b2));
    // the bounds: everything in the aim's region (B = 0) holds at shareMin, nothing at shareMax
    OpeningAim all(*ctx, o, &s);
    all.learnShare(1000.0, 1000.0);
    EXPECT_FLOAT_EQ(all.firstShare(), 0.25f);
    OpeningAim none(*ctx, o, &s);
    none.learnShare(1000.0, 0.0);
    EXPECT_FLOAT_EQ(none.firstShare(), 0.95f);
    // a fixed share is never moved
    o.learnShare = false;
    o.cosineShare = 0.6;
    OpeningAim fixed(*ctx, o, &s);
    fixed.learnShare(1000.0, 600.0);
    EXPECT_FLOAT_EQ(fixed.firstShare(), 0.6f);
    EXPECT_FALSE(fixed.report()["share_learned"].get<bool>());
}

TEST(OpeningAim, OptionsOutOfRangeAreOneLineErrors)
{
    OpeningAimOptions o;
    o.cosineShare = 1.0;
    EXPECT_THROW(validateOpeningAimOptions(o), Error);
    o.cosineShare = 0.0;
    EXPECT_THROW(validateOpeningAimOptions(o), Error);
    o = OpeningAimOptions{};
    o.minEntries = 0.0;
    EXPECT_THROW(validateOpeningAimOptions(o), Error);
    o = OpeningAimOptions{};
    o.minShare = 1.0;
    EXPECT_THROW(validateOpeningAimOptions(o), Error);
    o = OpeningAimOptions{};
    o.shareMin = 1.0;
    EXPECT_THROW(validateOpeningAimOptions(o), Error);
    o = OpeningAimOptions{};
    o.shareMax = 1.5;
    EXPECT_THROW(validateOpeningAimOptions(o), Error);
    o = OpeningAimOptions{};
    o.shareMin = 0.5;
    o.shareMax = 0.4;
    EXPECT_THROW(validateOpeningAimOptions(o), Error);
}

}  // namespace
}  // namespace fen
