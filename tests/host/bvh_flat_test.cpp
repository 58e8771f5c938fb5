// bvh_flat_test.cpp — the device layout: every packet referenced once, boxes nest, empty slots
// are empty, the stack bound is what the rows imply, and the layout is deterministic.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "bench/room_scene.h"
#include "bvh_flat.h"
#include "support/test_scenes.h"
#include "util/error.h"

namespace fen {
namespace {

Aabb childBox(const FlatBvh& f, std::size_t node, int k)
{
    const float* b = f.bounds(node);
    const int w = f.width;
    Aabb box;
    box.lo = glm::vec3(b[0 * w + k], b[2 * w + k], b[4 * w + k]);
    box.hi = glm::vec3(b[1 * w + k], b[3 * w + k], b[5 * w + k]);
    return box;
}

// Recomputes the stack bound from the rows and checks nesting and packet references.
int walk(const FlatBvh& f, std::uint32_t node, const Aabb* parent, std::vector<int>& packetRefs,
         std::vector<int>& nodeRefs, const std::vector<Triangle>& tris)
{
    nodeRefs[node] += 1;
    int children = 0, deepest = 0;
    for (int k = 0; k < f.width; ++k) {
        const std::uint32_t ref = f.child(node)[k];
        const Aabb box = childBox(f, node, k);
        if (ref == FEN_INVALID_ID) {
            EXPECT_TRUE(box.empty()) << "unused slot with a non-empty box";
            EXPECT_TRUE(std::isinf(box.lo.x) && box.lo.x > 0 && std::isinf(box.hi.x) && box.hi.x < 0);
            continue;
        }
        ++children;
        if (parent) {
            EXPECT_TRUE(parent->contains(box));
        }
        if (ref & FEN_LEAF_BIT) {
            const std::uint32_t p = ref & ~FEN_LEAF_BIT;
            EXPECT_LT(p, f.packets.size());
            packetRefs[p] += 1;
            const dev::TriPacket4& pk = f.packets[p];
            for (int lane = 0; lane < 4; ++lane) {
                EXPECT_LT(pk.prim[lane], tris.size());
                for (int v = 0; v < 3; ++v) {
                    const glm::vec3 q(pk.v[(3 * v + 0) * 4 + lane], pk.v[(3 * v + 1) * 4 + lane],
                                      pk.v[(3 * v + 2) * 4 + lane]);
                    EXPECT_TRUE(q.x >= box.lo.x && q.x <= box.hi.x && q.y >= box.lo.y &&
                                q.y <= box.hi.y && q.z >= box.lo.z && q.z <= box.hi.z)
                        << "packet vertex outside its leaf box";
                }
            }
        } else {
            EXPECT_LT(ref, f.nodeCount);
            deepest = std::max(deepest, walk(f, ref, &box, packetRefs, nodeRefs, tris));
        }
    }
    return std::max(children, children - 1 + deepest);
}

void checkFlat(const FlatBvh& f, const std::vector<Triangle>& tris)
{
    std::vector<int> packetRefs(f.packets.size(), 0), nodeRefs(f.nodeCount, 0);
    const int bound = walk(f, 0, nullptr, packetRefs, nodeRefs, tris);
    EXPECT_EQ(bound, f.stackBound);
    EXPECT_LE(f.stackBound, FEN_BVH_STACK_SIZE);
    for (int r : packetRefs)
        EXPECT_EQ(r, 1);
    for (int r : nodeRefs)
        EXPECT_EQ(r, 1);
    // Each kept triangle appears in lanes of exactly one packet.
    std::vector<int> tri(tris.size(), 0);
    for (const auto& p : f.packets) {
        std::uint32_t last = FEN_INVALID_ID;
        for (int lane = 0; lane < 4; ++lane) {
            if (p.prim[lane] != last)
                tri[p.prim[lane]] += 1;
            last = p.prim[lane];
        }
    }
    std::size_t kept = 0;
    for (std::size_t i = 0; i < tris.size(); ++i) {
        const bool degenerate = doubleArea2(tris[i]) == 0.0;
        EXPECT_EQ(tri[i], degenerate ? 0 : 1) << "triangle " << i;
        kept += !degenerate;
    }
    EXPECT_EQ(f.triangleCount, kept);
}

class FlatWidth : public ::testing::TestWithParam<int> {};

TEST_P(FlatWidth, RoomAndSoup)
{
    for (const auto& tris : {makeBenchRoom(2).scene.triangles, test::randomSoup(3000, 5)}) {
        const FlatBvh f = flattenBvh(buildBinnedSah(tris), tris, GetParam());
        checkFlat(f, tris);
    }
}

TEST_P(FlatWidth, EmptyAndTiny)
{
    const std::vector<Triangle> none;
    const FlatBvh e = flattenBvh(buildBinnedSah(none), none, GetParam());
    EXPECT_EQ(e.nodeCount, 1u);
    EXPECT_TRUE(e.packets.empty());
    checkFlat(e, none);
    for (std::size_t n : {1u, 3u, 5u, 17u}) {
        const auto tris = test::randomSoup(n, n);
        checkFlat(flattenBvh(buildBinnedSah(tris), tris, GetParam()), tris);
    }
}

TEST_P(FlatWidth, LayoutIsDeterministic)
{
    const auto tris = test::randomSoup(30000, 9);
    BuildOptions one, many;
    one.threads = 1;
    many.threads = 4;
    const FlatBvh a = flattenBvh(buildBinnedSah(tris, one), tris, GetParam());
    const FlatBvh b = flattenBvh(buildBinnedSah(tris, many), tris, GetParam());
    EXPECT_EQ(a.nodeWords, b.nodeWords);
    ASSERT_EQ(a.packets.size(), b.packets.size());
    EXPECT_EQ(0, std::memcmp(a.packets.data(), b.packets.data(), a.packetBytes()));
}

INSTANTIATE_TEST_SUITE_P(Widths, FlatWidth, ::testing::Values(2, 4, 8),
                         [](const auto& info) { return "bvh" + std::to_string(info.param); });

TEST(BvhFlat, BadWidthIsAnError)
{
    const auto tris = test::randomSoup(10, 1);
    EXPECT_THROW(flattenBvh(buildBinnedSah(tris), tris, 3), Error);
}

}  // namespace
}  // namespace fen
