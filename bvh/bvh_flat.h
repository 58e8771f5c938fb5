// bvh_flat.h — the device layout of a BVH: a binary SAH tree collapsed to 2, 4 or 8 children per
// node and written as BvhNode2/4/8 rows plus TriPacket4 leaves (kernels/shared/fen_bvh.h).
//
// Collapse rule (as in Embree's BVH4/8 builders): a wide node starts from a binary node's two
// children and repeatedly opens the inner child with the largest surface area until it has W
// children or none can be opened. Each binary leaf (<= 4 triangles) becomes one packet. Rows are
// written depth first, so the layout depends only on the tree, not on build threads.
#pragma once

#include <cstdint>
#include <vector>

#include "bvh_build.h"
#include "shared/fen_bvh.h"

namespace fen {

struct FlatBvh {
    int width = 8;
    std::size_t nodeCount = 0;
    std::vector<std::uint32_t> nodeWords;  // nodeCount rows of wordsPerNode() 32-bit words
    std::vector<dev::TriPacket4> packets;
    std::size_t triangleCount = 0;         // triangles in the tree (degenerate ones dropped)
    int stackBound = 0;                    // most traversal-stack entries any ray can need
    double flattenSeconds = 0.0;

    std::size_t wordsPerNode() const { return 8u * static_cast<std::size_t>(width); }
    std::size_t nodeBytes() const { return nodeWords.size() * 4; }
    std::size_t packetBytes() const { return packets.size() * sizeof(dev::TriPacket4); }
    // Row i: bounds() = lo_x[W] hi_x[W] lo_y[W] hi_y[W] lo_z[W] hi_z[W]; child() = W references.
    const float* bounds(std::size_t i) const
    {
        return reinterpret_cast<const float*>(nodeWords.data() + i * wordsPerNode());
    }
    const std::uint32_t* child(std::size_t i) const
    {
        return nodeWords.data() + i * wordsPerNode() + 6u * static_cast<std::size_t>(width);
    }
};

// Throws fen::Error if width is not 2, 4 or 8, or if the tree would need a deeper traversal
// stack than the kernels carry (FEN_BVH_STACK_SIZE).
FlatBvh flattenBvh(const BinaryBvh& bvh, const std::vector<Triangle>& tris, int width);

}  // namespace fen
