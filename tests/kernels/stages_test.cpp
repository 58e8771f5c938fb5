// stages_test.cpp — the shade and connect kernels on hand-made paths, against host formulas:
// the splat C = beta (rho/pi) |cos theta_x| / (d^2 A_pix cos^3 theta_c), the side rule (a surface
// lit from one side is not seen from the other), thin glass (reflect with probability R(theta),
// transmit with weight T), and the transmittance of connections through glass.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "cl/launch.h"
#include "scatter/first_bounce_guide.h"
#include "scatter/opening_aim.h"
#include "sensor/device_sensors.h"
#include "io/image.h"
#include "render/camera_setup.h"
#include "render/device_scene.h"
#include "shared/fen_render.h"
#include "support/cl_fixture.h"
#include "support/render_support.h"
#include "support/statistics.h"

namespace fen {
namespace {

using test::rect;

std::uint32_t asUint(float f)
{
    std::uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

// Runs intersect + shade (+ connect) on given paths in a scene, with a fixed camera.
struct Stages {
    ocl::Context& ctx;
    Scene scene;
    DeviceScene ds;
    dev::DevCamera cam;
    int width, height;

    Stages(ocl::Context& c, const Scene& s, int w, int h)
        : ctx(c), scene(s), ds(c, s, 8), cam(makeDevCamera(s.cameras.at(0), w, h)), width(w), height(h)
    {
    }

    struct Out {
        std::vector<dev::PathState> paths;
        std::vector<dev::Connection> connections;
        std::vector<std::uint64_t> accum;
        std::vector<std::uint64_t> counters;
        std::vector<std::uint64_t> cellStats;  // with statsScale > 0: FEN_CELL_STATS_WORDS per part
    };

    // statsScale > 0: connect.cl built to gather emission-cell statistics (a learning strategy's),
    // into `parts` parts.
    Out run(const std::vector<dev::PathState>& in, float fixedScale = 1.0f, float statsScale = 0.0f,
            std::size_t parts = 1)
    {
        const auto n = static_cast<std::uint32_t>(in.size());
        dev::RenderParams p{};
        p.seed = 7;
        p.max_depth = 64;
        p.pool_size = n;
        p.fixed_scale = fixedScale;
        p.stats_scale = statsScale;
        cl::Buffer params = ctx.buffer(CL_MEM_READ_ONLY, sizeof p, "params", &p);
        cl::Buffer paths = ctx.buffer(CL_MEM_READ_WRITE, n * sizeof(dev::PathState), "paths", in.data());
        cl::Buffer hits = ctx.buffer(CL_MEM_READ_WRITE, n * sizeof(dev::SurfaceHit), "hits");
        cl::Buffer splits = ctx.buffer(CL_MEM_READ_WRITE, n * sizeof(dev::SplitState), "split paths");
        cl::Buffer conns = ctx.buffer(CL_MEM_READ_WRITE, n * sizeof(dev::Connection), "connections");
        cl::Buffer camBuf = ctx.buffer(CL_MEM_READ_ONLY, sizeof cam, "camera", &cam);
        std::vector<std::uint64_t> zeros(FEN_CTR_COUNT, 0), accZero(std::size_t(width) * height * 6, 0);
        cl::Buffer counters = ctx.buffer(CL_MEM_READ_WRITE, zeros.size() * 8, "counters", zeros.data());
        cl::Buffer accum = ctx.buffer(CL_MEM_READ_WRITE, accZero.size() * 8, "accum", accZero.data());
        std::vector<std::uint64_t> statsZero(parts * FEN_CELL_STATS_WORDS, 0);
        cl::Buffer stats = ctx.buffer(CL_MEM_READ_WRITE, statsZero.size() * 8, "cell stats", statsZero.data());
        cl::Buffer noScale = ctx.buffer(CL_MEM_READ_ONLY, 4, "no pixel scale");
        const FirstBounceGuide noGuide(ctx, GuideOptions::off(), glm::dvec3(0.0), 1.0);  // off: the cosine
        const OpeningAim noAim(ctx, OpeningAimOptions::off(), nullptr);  // nothing aimed at
        const DeviceSensors noSensors(ctx);
        const auto defs = ds.defines();
        auto connectDefs = defs;
        if (statsScale > 0.0f)
            connectDefs.push_back("FEN_EMISSION_STATS=1");
        cl::Kernel isect(ctx.program("intersect.cl", defs), "intersect_paths");
        cl::Kernel shade(ctx.program("shade.cl", defs), "shade_paths");
        cl::Kernel connect(ctx.program("connect.cl", connectDefs), "connect_paths");
        ocl::setKernelArgs(isect, paths, hits, n, ds.bvh().nodes(), ds.bvh().packets());
        ocl::setKernelArgs(shade, params, paths, splits, hits, ds.primMaterial(), ds.materials(), ds.primUv(),
                           ds.texels(), camBuf, conns,
                           noGuide.params(), noGuide.tables(), noGuide.windowStats(), noAim.aim(), noAim.prims(),
                           noAim.stats(), noSensors.info(), noSensors.planes(),
                           noSensors.cellTable(), noSensors.bucketStart(), noSensors.bucketCells(),
                           noSensors.accumulators(), stats, noSensors.steer(), counters);
        ocl::setKernelArgs(connect, params, conns, ds.bvh().nodes(), ds.bvh().packets(), ds.primMaterial(),
                           ds.materials(), accum, stats, noScale, noGuide.stats(), noGuide.windowStats(), noAim.stats(),
                           counters);
        ocl::launch(ctx, isect, "intersect_paths", n);
        ocl::launch(ctx, shade, "shade_paths", n);
        ocl::launch(ctx, connect, "connect_paths", n);
        Out o;
        o.paths.resize(n);
        o.connections.resize(n);
        o.accum.resize(accZero.size());
        o.counters.resize(FEN_CTR_COUNT);
        auto& q = ctx.queue();
        q.enqueueReadBuffer(paths, CL_FALSE, 0, n * sizeof(dev::PathState), o.paths.data());
        q.enqueueReadBuffer(conns, CL_FALSE, 0, n * sizeof(dev::Connection), o.connections.data());
        q.enqueueReadBuffer(accum, CL_FALSE, 0, o.accum.size() * 8, o.accum.data());
        q.enqueueReadBuffer(counters, CL_TRUE, 0, o.counters.size() * 8, o.counters.data());
        o.cellStats.resize(statsZero.size());
        q.enqueueReadBuffer(stats, CL_TRUE, 0, o.cellStats.size() * 8, o.cellStats.data());
        return o;
    }
};

dev::PathState path(glm::vec3 org, glm::vec3 dir, glm::vec3 beta, std::uint32_t id)
{
    dev::PathState p{};
    dir = glm::normalize(dir);
    p.org = {org.x, org.y, org.z, 0};
    p.dir = {dir.x, dir.y, dir.z, 0};
    p.beta = {beta.x, beta.y, beta.z, 0};
    p.path_lo = id;
    p.flags = FEN_PATH_ALIVE;
    return p;
}

TEST(Stages, SplatFormulaAndSideRule)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    test::SceneBuilder b;
    const glm::vec3 rho(0.6f, 0.5f, 0.4f);
    b.add("plane", rect({-2, 0, -2}, {4, 0, 0}, {0, 0, 4}), b.material("grey", rho));
    b.camera({0.3, 2.0, 0.9}, {-0.2, 0.0, -0.1}, {0, 0, -1}, 60.0);
    const int W = 64, H = 48;
    Stages st(*ctx, b.build(), W, H);
    const CameraSpec& cam = st.scene.cameras[0];
    // Paths from above hitting points the camera sees, and from below (the camera sees the
    // top face: light on the bottom face must not reach it).
    std::vector<dev::PathState> in;
    std::vector<glm::dvec3> target;
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-0.8, 0.8);
    for (std::uint32_t i = 0; i < 200; ++i) {
        const glm::dvec3 x(u(rng), 0.0, u(rng));
        const double side = i % 4 == 3 ? -1.0 : 1.0;
        const glm::dvec3 from = x + glm::dvec3(0.3 * u(rng), side * 1.5, 0.3 * u(rng));
        in.push_back(path(glm::vec3(from), glm::vec3(x - from), glm::vec3(1000.0f, 2000.0f, 500.0f), i));
        target.push_back(x);
    }
    const auto out = st.run(in, 1024.0f);
    EXPECT_EQ(out.counters[FEN_CTR_BAD_CONTRIBUTIONS], 0u);
    const double tanY = std::tan(cam.yfovRad / 2), tanX = tanY * W / H;
    const double aPix = (2 * tanX / W) * (2 * tanY / H);
    int checked = 0;
    for (std::size_t i = 0; i < in.size(); ++i) {
        const dev::Connection& c = out.connections[i];
        const glm::dvec3 x = target[i];
        const glm::dvec3 toCam = cam.position - x;
        const double d2 = glm::dot(toCam, toCam), d = std::sqrt(d2);
        const double cosC = glm::dot(-toCam, cam.forward) / d;
        const bool fromBelow = i % 4 == 3;
        if (fromBelow) {
            EXPECT_EQ(asUint(c.org.w), FEN_INVALID_ID) << "light on the far side reached the camera";
            continue;
        }
        ASSERT_NE(asUint(c.org.w), FEN_INVALID_ID) << "path " << i;
        const double cosX = toCam.y / d;
        const glm::dvec3 beta(1000.0, 2000.0, 500.0);
        for (int ch = 0; ch < 3; ++ch) {
            const double expect = beta[ch] * rho[ch] / M_PI * cosX / (d2 * aPix * cosC * cosC * cosC);
            const float got = ch == 0 ? c.value.x : (ch == 1 ? c.value.y : c.value.z);
            EXPECT_NEAR(got, expect, 2e-5 * expect) << "path " << i << " channel " << ch;
        }
        // The pixel is the one the point projects to.
        const double sx = glm::dot(x - cam.position, cam.right) / (glm::dot(x - cam.position, cam.forward) * tanX);
        const double sy = glm::dot(x - cam.position, cam.up) / (glm::dot(x - cam.position, cam.forward) * tanY);
        const int px = int((sx + 1) / 2 * W), py = int((1 - sy) / 2 * H);
        EXPECT_EQ(asUint(c.org.w), std::uint32_t(py * W + px));
        ++checked;
    }
    EXPECT_GT(checked, 100);
    // Nothing blocks them, so every pixel holds exactly the sum of its contributions in fixed
    // point (scale 1024, each rounded to the nearest unit).
    std::vector<double> expectSum(std::size_t(W) * H * 3, 0.0), count(std::size_t(W) * H, 0.0);
    for (const auto& c : out.connections) {
        const std::uint32_t px = asUint(c.org.w);
        if (px == FEN_INVALID_ID)
            continue;
        expectSum[3 * px] += c.value.x * 1024.0;
        expectSum[3 * px + 1] += c.value.y * 1024.0;
        expectSum[3 * px + 2] += c.value.z * 1024.0;
        count[px] += 1.0;
    }
    for (std::size_t px = 0; px < count.size(); ++px)
        for (int ch = 0; ch < 3; ++ch) {
            EXPECT_EQ(out.accum[6 * px + 2 * ch + 1], 0u);
            EXPECT_NEAR(double(out.accum[6 * px + 2 * ch]), expectSum[3 * px + ch],
                        0.5 * count[px] + 1e-6 * expectSum[3 * px + ch])
                << "pixel " << px << " channel " << ch;
        }
    EXPECT_EQ(out.counters[FEN_CTR_SHADOW_RAYS], std::uint64_t(checked));
}

TEST(Stages, ContributionsFeedTheEmissionCellTheyCameFrom)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // A learning strategy's paths carry their emission cell part in beta.w; connect.cl adds each
    // contribution's luminance Y (at the pixels' scale) and Y^2 (at stats_scale) to that part, in
    // 128-bit fixed point, and counts it. Three parts, paths spread over them.
    test::SceneBuilder b;
    b.add("plane", rect({-2, 0, -2}, {4, 0, 0}, {0, 0, 4}), b.material("grey", glm::vec3(0.5f)));
    b.camera({0.0, 2.0, 0.5}, {0.0, 0.0, 0.0}, {0, 0, -1}, 60.0);
    Stages st(*ctx, b.build(), 32, 24);
    std::vector<dev::PathState> in;
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-0.5, 0.5);
    for (std::uint32_t i = 0; i < 300; ++i) {
        const glm::vec3 x(u(rng), 0.0f, u(rng));
        dev::PathState p = path(x + glm::vec3(0.1f, 1.0f, 0.0f), glm::vec3(-0.1f, -1.0f, 0.0f),
                                glm::vec3(50.0f + i, 80.0f, 20.0f), i);
        const std::uint32_t part = i % 3;
        std::memcpy(&p.beta.w, &part, 4);
        in.push_back(p);
    }
    const float scale = 64.0f, scaleSq = 1.0f / 4096.0f;
    const auto out = st.run(in, scale, scaleSq, 3);
    double sum[3] = {}, sumSq[3] = {}, n[3] = {};
    for (const auto& c : out.connections) {
        if (asUint(c.org.w) == FEN_INVALID_ID)
            continue;
        const std::uint32_t part = asUint(c.value.w);
        ASSERT_LT(part, 3u) << "the connection lost its cell";
        const double y = luminance(c.value.x, c.value.y, c.value.z);
        sum[part] += y * scale;
        sumSq[part] += y * y * scaleSq;
        n[part] += 1.0;
    }
    for (int k = 0; k < 3; ++k) {
        const std::uint64_t* w = out.cellStats.data() + FEN_CELL_STATS_WORDS * k;
        ASSERT_GT(n[k], 10.0);
        EXPECT_EQ(w[FEN_CELL_CONNECTIONS], std::uint64_t(n[k]));
        EXPECT_EQ(w[FEN_CELL_SUM_HI], 0u);
        EXPECT_NEAR(double(w[FEN_CELL_SUM_LO]), sum[k], 0.5 * n[k] + 1e-6 * sum[k]);
        EXPECT_NEAR(double(w[FEN_CELL_SUMSQ_LO]) + 18446744073709551616.0 * double(w[FEN_CELL_SUMSQ_HI]),
                    sumSq[k], 0.5 * n[k] + 1e-6 * sumSq[k]);
    }
    EXPECT_EQ(out.counters[FEN_CTR_STATS_OVERFLOWS], 0u);
}

TEST(Stages, ScatterStaysOnTheLitSideAndKeepsWeight)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    test::SceneBuilder b;
    const glm::vec3 rho(0.8f, 0.4f, 0.2f);
    b.add("plane", rect({-2, 0, -2}, {4, 0, 0}, {0, 0, 4}), b.material("m", rho));
    b.camera({0, 2, 0}, {0, 0, 0}, {0, 0, -1}, 40.0);
    Stages st(*ctx, b.build(), 16, 16);
    std::vector<dev::PathState> in;
    for (std::uint32_t i = 0; i < 20000; ++i)
        in.push_back(path({0.1f, i % 2 ? 1.0f : -1.0f, 0.2f}, {0, i % 2 ? -1.0f : 1.0f, 0}, {1, 1, 1}, i));
    const auto out = st.run(in);
    std::size_t alive = 0;
    for (std::size_t i = 0; i < in.size(); ++i) {
        const dev::PathState& p = out.paths[i];
        if (!(p.flags & FEN_PATH_ALIVE))
            continue;
        ++alive;
        const float side = i % 2 ? 1.0f : -1.0f;  // arrived from above: leaves upwards
        EXPECT_GT(p.dir.y * side, 0.0f);
        EXPECT_GT(p.org.y * side, 0.0f) << "origin not offset to the leaving side";
        EXPECT_FLOAT_EQ(p.beta.x, 1.0f);          // rho / q with q = max(rho) = 0.8
        EXPECT_FLOAT_EQ(p.beta.y, 0.5f);
        EXPECT_FLOAT_EQ(p.beta.z, 0.25f);
        EXPECT_EQ(p.depth, 1u);
    }
    // Russian roulette survival probability q = max(rho) = 0.8; binomial, 4 sigma.
    const double n = in.size(), sigma = std::sqrt(n * 0.8 * 0.2);
    EXPECT_NEAR(double(alive), 0.8 * n, 4 * sigma);
    EXPECT_EQ(out.counters[FEN_CTR_ALIVE], alive);
}

TEST(Stages, ThinGlassReflectsWithFresnelProbability)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    test::SceneBuilder b;
    const glm::vec3 T(0.9f, 0.8f, 0.7f);
    b.add("pane", rect({-2, 0, -2}, {4, 0, 0}, {0, 0, 4}), b.glass("glass", T, 1.5f));
    b.camera({0, 2, 0}, {0, 0, 0}, {0, 0, -1}, 40.0);
    Stages st(*ctx, b.build(), 16, 16);
    const float angle = 70.0f * float(M_PI) / 180.0f;  // from the normal: R is large, ~0.175
    const glm::vec3 dir(std::sin(angle), -std::cos(angle), 0.0f);
    std::vector<dev::PathState> in;
    for (std::uint32_t i = 0; i < 40000; ++i)
        in.push_back(path(-dir, dir, {1, 1, 1}, i));
    const auto out = st.run(in);
    const double ci = std::cos(angle), ct = std::sqrt(1 - (1 - ci * ci) / 2.25);
    const double rs = (ci - 1.5 * ct) / (ci + 1.5 * ct), rp = (1.5 * ci - ct) / (1.5 * ci + ct);
    const double R = 0.5 * (rs * rs + rp * rp);
    std::size_t reflected = 0;
    for (const auto& p : out.paths) {
        ASSERT_TRUE(p.flags & FEN_PATH_ALIVE);
        if (p.dir.y > 0.0f) {
            ++reflected;
            EXPECT_NEAR(p.dir.x, dir.x, 1e-6);
            EXPECT_NEAR(p.dir.y, -dir.y, 1e-6);
            EXPECT_FLOAT_EQ(p.beta.x, 1.0f);  // reflection keeps the weight
            EXPECT_GT(p.org.y, 0.0f);
        } else {
            EXPECT_NEAR(p.dir.x, dir.x, 1e-6);  // straight through, no refraction offset
            EXPECT_FLOAT_EQ(p.beta.x, T.x);
            EXPECT_FLOAT_EQ(p.beta.y, T.y);
            EXPECT_FLOAT_EQ(p.beta.z, T.z);
            EXPECT_LT(p.org.y, 0.0f);
        }
    }
    for (const auto& c : out.connections)
        EXPECT_EQ(asUint(c.org.w), FEN_INVALID_ID) << "glass is specular: no camera connection";
    const double n = in.size();
    EXPECT_NEAR(double(reflected), R * n, 4 * std::sqrt(n * R * (1 - R))) << "R = " << R;
}

TEST(Stages, ConnectionsThroughGlassAreAttenuatedAndOpaqueBlocks)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    // A lit floor at y = 0 seen by a camera at y = 3 through two panes (y = 1, 2), and through a
    // third region covered by an opaque board instead.
    test::SceneBuilder b;
    const glm::vec3 T1(0.9f), T2(0.5f, 0.6f, 0.7f);
    b.add("floor", rect({-3, 0, -3}, {6, 0, 0}, {0, 0, 6}), b.material("floor", glm::vec3(0.5f)));
    b.add("pane1", rect({-3, 1, -3}, {6, 0, 0}, {0, 0, 3}), b.glass("g1", T1, 1.5f));
    b.add("pane2", rect({-3, 2, -3}, {6, 0, 0}, {0, 0, 3}), b.glass("g2", T2, 1.33f));
    b.add("board", rect({-3, 1.5f, 0}, {6, 0, 0}, {0, 0, 3}), b.material("board", glm::vec3(0.5f)));
    b.camera({0, 3, 0}, {0, 0, 0}, {0, 0, -1}, 90.0);
    const int W = 32, H = 32;
    Stages st(*ctx, b.build(), W, H);
    // Paths arriving at the floor from just above it (below the panes and the board).
    std::vector<dev::PathState> in;
    std::vector<glm::dvec3> x;
    for (std::uint32_t i = 0; i < 64; ++i) {
        const glm::dvec3 p(-1.5 + 3.0 * (i % 8) / 8.0 + 0.1, 0.0, (i < 32 ? -1.5 : 1.0) + 0.05 * (i % 8));
        in.push_back(path(glm::vec3(p + glm::dvec3(0, 0.5, 0)), {0, -1, 0}, {1, 1, 1}, i));
        x.push_back(p);
    }
    const auto out = st.run(in, 1048576.0f);
    const CameraSpec& cam = st.scene.cameras[0];
    auto fresnel = [](double c, double eta) {
        const double ct = std::sqrt(1 - (1 - c * c) / (eta * eta));
        const double rs = (c - eta * ct) / (c + eta * ct), rp = (eta * c - ct) / (eta * c + ct);
        return 0.5 * (rs * rs + rp * rp);
    };
    std::vector<double> expectPixel(std::size_t(W) * H * 3, 0.0);
    for (std::size_t i = 0; i < in.size(); ++i) {
        const dev::Connection& c = out.connections[i];
        ASSERT_NE(asUint(c.org.w), FEN_INVALID_ID);
        const glm::dvec3 v = glm::normalize(cam.position - x[i]);
        const double cosV = v.y;  // panes are horizontal
        const bool underGlass = x[i].z < 0.0;
        for (int ch = 0; ch < 3; ++ch) {
            const double t = underGlass ? T1[ch] * (1 - fresnel(cosV, 1.5)) * T2[ch] * (1 - fresnel(cosV, 1.33)) : 0.0;
            const float val = ch == 0 ? c.value.x : (ch == 1 ? c.value.y : c.value.z);
            expectPixel[3 * asUint(c.org.w) + ch] += val * t;
        }
    }
    for (std::size_t k = 0; k < expectPixel.size(); ++k) {
        const std::size_t p = k / 3, ch = k % 3;
        EXPECT_EQ(out.accum[6 * p + 2 * ch + 1], 0u);  // small values: the high word stays 0
        const double got = out.accum[6 * p + 2 * ch] / 1048576.0;
        EXPECT_NEAR(got, expectPixel[k], 1e-5 * expectPixel[k] + 1e-5) << "accumulator " << k;
    }
    EXPECT_EQ(out.counters[FEN_CTR_SHADOW_RAYS], in.size());
}

}  // namespace
}  // namespace fen
