// uniform_sampling_test.cpp — the `uniform` strategy's emission against the density it claims
// (DESIGN.md §3.1): every line enters the emission box, uniformly over its silhouette (which face,
// and where on it: chi-square, p > 1e-3, fixed seeds); the source table shares the flux the box
// receives; and every emitted path's weight is the radiance over its exact density, so the mean
// weight is the luminous flux into the box (4 sigma of the sample's standard error).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cl/launch.h"
#include "emission/emission_sphere.h"
#include "emission/light_levels.h"
#include "emission/uniform_emission.h"
#include "emission/uniform_strategy.h"
#include "io/image.h"
#include "shared/fen_render.h"
#include "sky/goniogram.h"
#include "sky/sky_spec.h"
#include "support/cl_fixture.h"
#include "support/emit_probe.h"
#include "support/render_support.h"
#include "support/statistics.h"

namespace fen {
namespace {

using test::rect;

constexpr double kMinP = 1e-3;

dev::RenderParams paramsAround(const EmissionBox& box)
{
    dev::RenderParams p{};
    const glm::dvec3 c = box.min + 0.5 * box.size;
    p.sphere = {float(c.x), float(c.y), float(c.z), float(0.5 * glm::length(box.size) * 1.001 + 1e-3)};
    return p;
}

// The i-th line's origin along `dir` (unit), and the silhouette area the device reports.
std::vector<cl_float4> runBoxLines(ocl::Context& ctx, const EmissionBox& box, const glm::dvec3& dir,
                                   std::uint32_t n)
{
    const dev::RenderParams p = paramsAround(box);
    const dev::SourceParams src = sourceParams(makeIntegerCdf({1.0}), glm::dvec3(1.0), &box);
    cl::Buffer pb = ctx.buffer(CL_MEM_READ_ONLY, sizeof p, "render parameters", &p);
    cl::Buffer sb = ctx.buffer(CL_MEM_READ_ONLY, sizeof src, "source parameters", &src);
    cl::Buffer out = ctx.buffer(CL_MEM_WRITE_ONLY, std::size_t{n} * 16, "lines");
    cl::Kernel k(ctx.program("test_uniform_probes.cl"), "box_line_probe");
    ocl::setKernelArgs(k, pb, sb, float(dir.x), float(dir.y), float(dir.z), out, n, std::uint32_t{3});
    ocl::launch(ctx, k, "box_line_probe", n);
    std::vector<cl_float4> v(n);
    ctx.queue().enqueueReadBuffer(out, CL_TRUE, 0, v.size() * 16, v.data());
    return v;
}

// Where the line o + t dir first enters the box (slabs, in double): the face's axis, or -1 when
// it misses (or starts inside); *t the distance.
int entryFace(const EmissionBox& box, const glm::dvec3& o, const glm::dvec3& dir, double* t)
{
    const glm::dvec3 hi = box.min + box.size;
    double tIn = -INFINITY, tOut = INFINITY;
    int face = -1;
    for (int a = 0; a < 3; ++a) {
        if (dir[a] == 0.0) {
            if (o[a] < box.min[a] || o[a] > hi[a])
                return -1;
            continue;
        }
        const double t0 = (box.min[a] - o[a]) / dir[a], t1 = (hi[a] - o[a]) / dir[a];
        if (std::min(t0, t1) > tIn)
            tIn = std::min(t0, t1), face = a;
        tOut = std::min(tOut, std::max(t0, t1));
    }
    *t = tIn;
    return tIn > 0.0 && tIn <= tOut + 1e-6 * glm::length(box.size) ? face : -1;
}

TEST(UniformSampling, LinesCoverTheBoxSilhouetteUniformly)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const EmissionBox box{glm::dvec3(-3.0, 0.0, -4.5), glm::dvec3(6.0, 2.8, 9.0)};
    // Oblique from either side, straight down (one face only), grazing with no z (two faces).
    for (glm::dvec3 d : {glm::dvec3(0.3, -0.8, 0.52), glm::dvec3(-0.6, -0.3, -0.74), glm::dvec3(0.0, -1.0, 0.0),
                         glm::dvec3(0.7, -0.1, 0.0)}) {
        d = glm::normalize(d);
        const glm::dvec3 dir{glm::vec3(d)};  // as the device sees it
        const std::uint32_t n = 200000;
        const auto v = runBoxLines(*ctx, box, dir, n);
        const double A = box.silhouetteArea(dir);
        // The face each line enters by, and where on it in [0,1)^2 (an 8 x 8 grid).
        constexpr int kGrid = 8;
        std::vector<double> obs(3 * kGrid * kGrid, 0.0);
        std::size_t misses = 0;
        for (const auto& s : v) {
            ASSERT_NEAR(s.s[3], A, 1e-5 * A) << "silhouette area along " << d.x << " " << d.y << " " << d.z;
            const glm::dvec3 o(s.s[0], s.s[1], s.s[2]);
            double t = 0.0;
            const int face = entryFace(box, o, dir, &t);
            if (face < 0) {
                ++misses;
                continue;
            }
            const glm::dvec3 x = o + t * dir;
            auto cell = [&](int a) {
                return std::clamp(static_cast<int>((x[a] - box.min[a]) / box.size[a] * kGrid), 0, kGrid - 1);
            };
            obs[static_cast<std::size_t>((face * kGrid + cell((face + 1) % 3)) * kGrid + cell((face + 2) % 3))] += 1.0;
        }
        EXPECT_EQ(misses, 0u) << "every line must enter the box";
        // Each face by its projected area |d_a| x (its area), uniform on it.
        std::vector<double> o2, e2;
        for (int a = 0; a < 3; ++a) {
            const double share = std::fabs(dir[a]) * box.size[(a + 1) % 3] * box.size[(a + 2) % 3] / A;
            for (int c = 0; c < kGrid * kGrid; ++c) {
                const double got = obs[static_cast<std::size_t>(a * kGrid * kGrid + c)];
                if (share == 0.0) {
                    EXPECT_EQ(got, 0.0) << "a face the light does not see";
                    continue;
                }
                o2.push_back(got);
                e2.push_back(n * share / (kGrid * kGrid));
            }
        }
        EXPECT_GT(test::chiSquarePValue(o2, e2), kMinP) << "along " << d.x << " " << d.y << " " << d.z;
    }
}

TEST(UniformSampling, SourcesShareTheFluxIntoTheBox)
{
    // The table's sky flux is ∫ A(w) g dw: per axis, the faces' area times the illuminance of a
    // plane facing each way (Goniogram::illuminance, which sums F_ij . n over the cells a plane
    // does not cut; the table sums two clipped integrals per cell and axis); the uneven sky's
    // cells from 45 to 100 degrees of azimuth straddle the plane z = 0.
    Scene scene;
    scene.bounds.grow(glm::vec3(-3.0f, 0.0f, -4.5f));
    scene.bounds.grow(glm::vec3(3.0f, 2.8f, 4.5f));
    scene.sun.present = true;
    scene.sun.illuminanceRgb_lux = glm::dvec3(8e4, 9e4, 1e5);
    scene.sun.travelDirection = glm::normalize(glm::dvec3(0.3, -0.8, 0.52));
    const Goniogram g = test::unevenTableSky();
    const UniformSources u = setupUniformEmission(scene, makeSkyTables(g), g);
    const glm::dvec3 s = u.box.size;
    EXPECT_GT(s.x, 6.0);  // enlarged: geometry on the faces lies inside
    EXPECT_LT(s.x, 6.0 * 1.001 + 0.01);
    double sky = 0.0;
    for (int a = 0; a < 3; ++a) {
        glm::dvec3 n(0.0);
        n[a] = 1.0;
        sky += s[(a + 1) % 3] * s[(a + 2) % 3] * (g.illuminance(n) + g.illuminance(-n));
    }
    EXPECT_NEAR(u.skyFlux, sky, 1e-5 * sky);
    const double sunY = luminance(8e4, 9e4, 1e5);
    EXPECT_NEAR(u.sunFlux, sunY * u.box.silhouetteArea(scene.sun.travelDirection), 1e-9 * u.sunFlux);
    EXPECT_NEAR(u.pSun, u.sunFlux / (u.sunFlux + u.skyFlux), 1e-6);
    // With the ground's glow below the horizon the lower hemisphere's cells send their light in
    // too: a uniform L_g over it adds ∫_lower |w_a| L_g dw = pi L_g through each pair of faces.
    const double Lg = 300.0;
    const Goniogram gg = g.withGround(Lg);
    const UniformSources ug = setupUniformEmission(scene, makeSkyTables(gg), gg);
    const double ground = M_PI * Lg * (s.y * s.z + s.z * s.x + s.x * s.y);
    EXPECT_NEAR(ug.skyFlux - u.skyFlux, ground, 1e-5 * ug.skyFlux);
    EXPECT_EQ(ug.sunFlux, u.sunFlux);
}

// A floor and a wall (the box is not flat), a parallel sun and a CIE sky: E[Y(weight)] is
// E_Y A(sun) + ∫ A g dw, the strategy's emittedFluxPerPath, if every path's weight is the
// radiance over its exact density. Every origin starts outside the bounding sphere and its
// line enters the box. With a ground (albedo rhoG > 0) g covers the whole sphere, and the
// lines from below the horizon travel upwards into the box.
void expectWeightsCarryTheFluxIntoTheBox(ocl::Context& ctx, double rhoG)
{
    test::SceneBuilder b;
    const int m = b.material("m", glm::vec3(0.5f));
    b.add("floor", rect({-3, 0, -4}, {7, 0, 0}, {0, 0, 9}), m);
    b.add("wall", rect({-3, 0, -4}, {7, 0, 0}, {0, 2.5f, 0}), m);
    b.sun(35.0, 160.0, 40000.0);
    b.cieSky(12, 2500.0, 35.0, 160.0);
    b.camera({0, 1, 2}, {0, 1, 0}, {0, 1, 0}, 60.0);
    Scene scene = b.build();
    scene.sky.groundAlbedo = rhoG;
    const auto g = buildSky(scene);
    ASSERT_EQ(g->hasGround(), rhoG > 0.0);
    const SkyTables tables = makeSkyTables(g);
    const DeviceSky sky(ctx, tables);
    const double fixedScale = std::ldexp(1.0, 40) / referenceLuminance(scene, tables);
    auto strategy = makeUniformStrategy({ctx, scene, tables, g, sky, 8, fixedScale});
    const EmissionBox box = emissionBox(scene);

    const dev::RenderParams params = test::emissionParams(scene, tables, 9);
    glm::dvec3 centre;
    double radius;
    emissionSphere(scene, &centre, &radius);
    const std::uint32_t n = 1u << 20;
    cl::Kernel k(ctx.program("test_uniform_probes.cl"), "uniform_emit_probe");
    const test::EmittedPaths e = test::runEmitProbe(ctx, k, "uniform_emit_probe", *strategy, params, n);
    const auto &vb = e.beta, &vo = e.org, &vd = e.dir;

    std::vector<double> y(n);
    std::size_t misses = 0, inside = 0, upwards = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        const auto& w = vb[i].s;
        ASSERT_TRUE(std::isfinite(w[0]) && std::isfinite(w[1]) && std::isfinite(w[2])) << "path " << i;
        y[i] = luminance(w[0], w[1], w[2]);
        const glm::dvec3 o(vo[i].s[0], vo[i].s[1], vo[i].s[2]), d(vd[i].s[0], vd[i].s[1], vd[i].s[2]);
        inside += glm::length(o - centre) < radius * (1.0 - 1e-6);
        double t = 0.0;
        misses += entryFace(box, o, d, &t) < 0;
        upwards += d.y > 0.0;
    }
    EXPECT_EQ(inside, 0u) << "origins must start outside the bounding sphere";
    EXPECT_EQ(misses, 0u) << "every line must enter the box";
    if (rhoG > 0.0) {
        EXPECT_GT(upwards, n / 20) << "the ground's light travels upwards";
    } else {
        EXPECT_EQ(upwards, 0u);
    }
    const auto ms = test::meanAndStdErr(y);
    const double flux = strategy->emittedFluxPerPath();
    std::printf("[ uniform  ] ground albedo %g: mean weight %.6g lm, flux into the box %.6g lm, se %.2g (%+.2f sigma)\n",
                rhoG, ms.mean, flux, ms.se, (ms.mean - flux) / ms.se);
    EXPECT_NEAR(ms.mean, flux, 4.0 * ms.se) << "relative se " << ms.se / ms.mean;
    EXPECT_LT(ms.se / ms.mean, 3e-3) << "the estimate must be sharp enough to mean something";
}

TEST(UniformSampling, WeightsCarryTheFluxIntoTheBox)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    expectWeightsCarryTheFluxIntoTheBox(*ctx, 0.0);
}

TEST(UniformSampling, WeightsCarryTheFluxIntoTheBoxFromTheGroundToo)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    expectWeightsCarryTheFluxIntoTheBox(*ctx, 0.3);
}

}  // namespace
}  // namespace fen
