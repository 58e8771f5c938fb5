// bvh_build.h — binary BVH over a triangle soup by the surface area heuristic (SAH).
//
// buildBinnedSah is the production builder: centroid binning (Wald, "On fast construction of
// SAH-based bounding volume hierarchies", 2007), all three axes in one pass, multi-threaded over
// subtrees and, for large nodes, over the binning pass itself. buildSweepSah evaluates every
// split position exactly (O(n log^2 n)); it exists to measure how close binning gets.
// Invariants of the result: every non-degenerate triangle is in exactly one leaf; a leaf holds
// 1..maxLeafSize triangles; every box contains its subtree. Triangles with zero area (computed in
// double) are dropped -- they can never be hit -- and counted; a non-finite vertex is an error.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry.h"

namespace fen {

struct BuildOptions {
    int maxLeafSize = 4;        // one TriPacket4 per leaf
    int packetSize = 4;         // SAH counts leaf cost in packets of this many (1 = triangles)
    int bins = 32;
    float traversalCost = 1.0f;  // SAH: cost of visiting a node, in packet tests
    int maxSahDepth = 40;       // deeper, split at the median: bounds the traversal stack
    int threads = 0;            // 0 = all hardware threads
};

struct BinaryNode {
    Aabb box;
    std::uint32_t first = 0;  // leaf: first index into primOrder; inner: left child (right = first+1)
    std::uint32_t count = 0;  // leaf: number of triangles (>= 1); inner: 0
    bool isLeaf() const { return count > 0; }
};

struct BinaryBvh {
    std::vector<BinaryNode> nodes;       // nodes[0] is the root; empty when no triangle remains
    std::vector<std::uint32_t> primOrder;  // triangle ids, leaf by leaf
    std::size_t droppedDegenerate = 0;
    int depth = 0;                       // edges on the longest root-to-leaf path
    double buildSeconds = 0.0;
};

BinaryBvh buildBinnedSah(const std::vector<Triangle>& tris, const BuildOptions& opt = {});
BinaryBvh buildSweepSah(const std::vector<Triangle>& tris, const BuildOptions& opt = {});

// Expected cost of a random ray under the SAH: sum over inner nodes of A(n)/A(root)*traversalCost
// plus sum over leaves of A(l)/A(root)*packetCost(count). Comparable between trees of the same
// triangles built with the same options.
double sahCost(const BinaryBvh& bvh, const BuildOptions& opt = {});

// Cost of testing n triangles: the number of packets they fill (or n if packetSize is 1).
float packetCost(std::uint32_t n, const BuildOptions& opt);

}  // namespace fen
