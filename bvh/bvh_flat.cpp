// bvh_flat.cpp — collapse a binary BVH to W-wide rows and pack leaves (bvh_flat.h).
#include "bvh_flat.h"

#include <chrono>
#include <cstring>
#include <limits>

#include "util/error.h"

namespace fen {

static_assert(sizeof(dev::BvhNode2) == 32 * 2, "BvhNode2 row must be 8W words");
static_assert(sizeof(dev::BvhNode4) == 32 * 4, "BvhNode4 row must be 8W words");
static_assert(sizeof(dev::BvhNode8) == 32 * 8, "BvhNode8 row must be 8W words");

namespace {

class Flattener {
public:
    Flattener(const BinaryBvh& bvh, const std::vector<Triangle>& tris, FlatBvh& out)
        : bvh_(bvh), tris_(tris), out_(out), w_(static_cast<std::size_t>(out.width))
    {
    }

    // Writes the row for a wide node whose children are `kids` (binary node indices); returns
    // (row index, stack entries its subtree may need).
    std::pair<std::uint32_t, int> emit(std::vector<std::uint32_t> kids)
    {
        while (kids.size() < w_) {
            int best = -1;
            float bestArea = -1.0f;
            for (std::size_t k = 0; k < kids.size(); ++k) {
                const BinaryNode& n = bvh_.nodes[kids[k]];
                if (!n.isLeaf() && n.box.halfArea() > bestArea) {
                    bestArea = n.box.halfArea();
                    best = static_cast<int>(k);
                }
            }
            if (best < 0)
                break;
            const std::uint32_t left = bvh_.nodes[kids[static_cast<std::size_t>(best)]].first;
            kids[static_cast<std::size_t>(best)] = left;
            kids.push_back(left + 1);
        }

        const std::uint32_t row = static_cast<std::uint32_t>(out_.nodeCount++);
        out_.nodeWords.resize(out_.nodeCount * out_.wordsPerNode());
        initRow(row);
        int deepest = 0;
        for (std::size_t k = 0; k < kids.size(); ++k) {
            const BinaryNode& n = bvh_.nodes[kids[k]];
            std::uint32_t ref;
            if (n.isLeaf()) {
                ref = FEN_LEAF_BIT | emitPacket(n);
            } else {
                const auto [childRow, need] = emit({n.first, n.first + 1});
                ref = childRow;
                deepest = std::max(deepest, need);
            }
            setChild(row, k, n.box, ref);
        }
        // A node with c hit children transiently holds c entries (pushed, then one popped), and
        // leaves c - 1 of them below whatever its children push.
        const int c = static_cast<int>(kids.size());
        return {row, std::max(c, c - 1 + deepest)};
    }

    // The root of an empty tree, or of a tree whose root is a leaf.
    void emitRootOnly(const BinaryNode* leaf)
    {
        out_.nodeCount = 1;
        out_.nodeWords.resize(out_.wordsPerNode());
        initRow(0);
        if (leaf)
            setChild(0, 0, leaf->box, FEN_LEAF_BIT | emitPacket(*leaf));
    }

private:
    void initRow(std::uint32_t row)
    {
        std::uint32_t* words = out_.nodeWords.data() + row * out_.wordsPerNode();
        float* b = reinterpret_cast<float*>(words);
        const float inf = std::numeric_limits<float>::infinity();
        for (std::size_t k = 0; k < w_; ++k)
            for (std::size_t a = 0; a < 3; ++a) {
                b[(2 * a) * w_ + k] = inf;       // lo
                b[(2 * a + 1) * w_ + k] = -inf;  // hi: an empty box no ray hits
            }
        for (std::size_t k = 0; k < 2 * w_; ++k)
            words[6 * w_ + k] = k < w_ ? FEN_INVALID_ID : 0u;
    }

    void setChild(std::uint32_t row, std::size_t k, const Aabb& box, std::uint32_t ref)
    {
        std::uint32_t* words = out_.nodeWords.data() + row * out_.wordsPerNode();
        float* b = reinterpret_cast<float*>(words);
        for (std::size_t a = 0; a < 3; ++a) {
            b[(2 * a) * w_ + k] = box.lo[static_cast<int>(a)];
            b[(2 * a + 1) * w_ + k] = box.hi[static_cast<int>(a)];
        }
        words[6 * w_ + k] = ref;
    }

    std::uint32_t emitPacket(const BinaryNode& leaf)
    {
        dev::TriPacket4 p;
        std::memset(&p, 0, sizeof p);
        for (std::uint32_t lane = 0; lane < 4; ++lane) {
            const std::uint32_t id = bvh_.primOrder[leaf.first + std::min(lane, leaf.count - 1)];
            const Triangle& t = tris_[id];
            const glm::vec3* v[3] = {&t.p0, &t.p1, &t.p2};
            for (int k = 0; k < 3; ++k)
                for (int a = 0; a < 3; ++a)
                    p.v[(3 * k + a) * 4 + lane] = (*v[k])[a];
            p.prim[lane] = id;
        }
        out_.packets.push_back(p);
        out_.triangleCount += leaf.count;
        return static_cast<std::uint32_t>(out_.packets.size() - 1);
    }

    const BinaryBvh& bvh_;
    const std::vector<Triangle>& tris_;
    FlatBvh& out_;
    std::size_t w_;
};

}  // namespace

FlatBvh flattenBvh(const BinaryBvh& bvh, const std::vector<Triangle>& tris, int width)
{
    if (width != 2 && width != 4 && width != 8)
        throw Error(cat("BVH width must be 2, 4 or 8, not ", width));
    const auto t0 = std::chrono::steady_clock::now();
    FlatBvh out;
    out.width = width;
    // A binary tree of L leaves has 2L - 1 nodes; every wide row has at least two children, so
    // there are fewer rows than leaves.
    const std::size_t leaves = (bvh.nodes.size() + 1) / 2;
    out.packets.reserve(leaves);
    out.nodeWords.reserve(std::max<std::size_t>(1, leaves) * out.wordsPerNode());
    Flattener f(bvh, tris, out);
    if (bvh.nodes.empty()) {
        f.emitRootOnly(nullptr);
        out.stackBound = 0;
    } else if (bvh.nodes[0].isLeaf()) {
        f.emitRootOnly(&bvh.nodes[0]);
        out.stackBound = 1;
    } else {
        out.stackBound = f.emit({bvh.nodes[0].first, bvh.nodes[0].first + 1}).second;
    }
    if (out.stackBound > FEN_BVH_STACK_SIZE)
        throw Error(cat("the BVH needs a traversal stack of ", out.stackBound,
                        " entries; the kernels carry ", FEN_BVH_STACK_SIZE));
    out.flattenSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

}  // namespace fen
