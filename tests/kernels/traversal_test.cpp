// traversal_test.cpp — the closest-hit and any-hit kernels against the CPU reference (bit for bit)
// and brute force, for every BVH width, on random soups, the benchmark room, a large scene.
#include <gtest/gtest.h>

#include "bench/room_scene.h"
#include "trace_support.h"

namespace fen {
namespace {

using test::TracedScene;

class Traversal : public ::testing::TestWithParam<int> {};

std::vector<RefRay> randomRays(std::size_t n, glm::vec3 center, float spread, std::uint64_t seed,
                               float tmax = std::numeric_limits<float>::infinity())
{
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> u(-0.5f, 0.5f);
    std::vector<RefRay> rays;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3 o = center + spread * glm::vec3(u(rng), u(rng), u(rng));
        rays.push_back(test::refRay(o, test::uniformSphere(rng) * (0.5f + u(rng) + 0.5f), 0.0f, tmax));
    }
    return rays;
}

TEST_P(Traversal, RandomSoup)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    TracedScene s(*ctx, test::randomSoup(3000, 1), GetParam());
    auto rays = randomRays(20000, glm::vec3(0), 12.0f, 2);
    // segments too: finite tmax exercises the any-hit cut-off
    const auto segs = randomRays(20000, glm::vec3(0), 12.0f, 3, 4.0f);
    rays.insert(rays.end(), segs.begin(), segs.end());
    EXPECT_EQ(test::deviceVsReference(s, rays), 0u);
    const auto c = test::deviceVsBruteForce(s, rays);
    EXPECT_EQ(c.disagreements, 0u);
    EXPECT_LE(c.borderline, rays.size() / 1000);
}

TEST_P(Traversal, BenchmarkRoom)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const BenchScene room = makeBenchRoom(1);
    TracedScene s(*ctx, room.scene.triangles, GetParam());
    std::vector<RefRay> rays;
    for (const auto& r : makeClosestRays(room, 20000, 5))
        rays.push_back(test::refRay({r.org_tmin.x, r.org_tmin.y, r.org_tmin.z},
                                    {r.dir_tmax.x, r.dir_tmax.y, r.dir_tmax.z}, r.org_tmin.w, r.dir_tmax.w));
    for (const auto& r : makeOcclusionSegments(room, 20000, 6))
        rays.push_back(test::refRay({r.org_tmin.x, r.org_tmin.y, r.org_tmin.z},
                                    {r.dir_tmax.x, r.dir_tmax.y, r.dir_tmax.z}, r.org_tmin.w, r.dir_tmax.w));
    EXPECT_EQ(test::deviceVsReference(s, rays), 0u);
    // The room is closed: every closest-hit ray hits.
    const auto hits = s.queries->closest(test::toDevice(rays));
    for (std::size_t i = 0; i < 20000; ++i)
        ASSERT_NE(hits[i].prim, FEN_INVALID_ID) << "ray " << i << " escaped the closed room";
    const std::vector<RefRay> few(rays.begin(), rays.begin() + 300);
    EXPECT_EQ(test::deviceVsBruteForce(s, few).disagreements, 0u);
}

TEST_P(Traversal, AnyHitAgreesWithClosestHit)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    TracedScene s(*ctx, test::randomSoup(2000, 4, glm::vec3(0), 8.0f, 2.0f), GetParam());
    const auto rays = randomRays(30000, glm::vec3(0), 10.0f, 7, 3.0f);
    const auto hits = s.queries->closest(test::toDevice(rays));
    const auto occ = s.queries->any(test::toDevice(rays));
    std::size_t bad = 0;
    for (std::size_t i = 0; i < rays.size(); ++i)
        bad += (occ[i] != 0) != (hits[i].prim != FEN_INVALID_ID);
    EXPECT_EQ(bad, 0u);
}

TEST_P(Traversal, MillionTriangles)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    TracedScene s(*ctx, test::randomSoup(1u << 20, 8, glm::vec3(0), 100.0f, 1.0f), GetParam());
    EXPECT_EQ(s.flat.triangleCount, 1u << 20);
    EXPECT_LE(s.flat.stackBound, FEN_BVH_STACK_SIZE);
    const auto rays = randomRays(20000, glm::vec3(0), 120.0f, 9);
    EXPECT_EQ(test::deviceVsReference(s, rays), 0u);
    const std::vector<RefRay> few(rays.begin(), rays.begin() + 100);
    EXPECT_EQ(test::deviceVsBruteForce(s, few).disagreements, 0u);
}

INSTANTIATE_TEST_SUITE_P(Widths, Traversal, ::testing::Values(2, 4, 8),
                         [](const auto& info) { return "bvh" + std::to_string(info.param); });

}  // namespace
}  // namespace fen
