// bvh_build.cpp — binned and full-sweep SAH builders (bvh_build.h).
#include "bvh_build.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <future>
#include <numeric>
#include <thread>

#include "util/error.h"

namespace fen {

namespace {

struct PrimRef {
    Aabb box;
    glm::vec3 centroid;
    std::uint32_t id;
};

}  // namespace

float packetCost(std::uint32_t n, const BuildOptions& opt)
{
    if (opt.packetSize <= 1)
        return static_cast<float>(n);
    return static_cast<float>((n + static_cast<std::uint32_t>(opt.packetSize) - 1) /
                              static_cast<std::uint32_t>(opt.packetSize));
}

namespace {

struct RangeBounds {
    Aabb box;       // of the triangles
    Aabb centroids; // of their centroids
};

// The triangles that can be hit, as references; throws on a non-finite vertex.
std::vector<PrimRef> makeRefs(const std::vector<Triangle>& tris, std::size_t* dropped)
{
    std::vector<PrimRef> refs;
    refs.reserve(tris.size());
    *dropped = 0;
    for (std::size_t i = 0; i < tris.size(); ++i) {
        const Triangle& t = tris[i];
        if (!isFinite(t.p0) || !isFinite(t.p1) || !isFinite(t.p2))
            throw Error(cat("triangle ", i, " has a non-finite vertex coordinate"));
        if (doubleArea2(t) == 0.0) {
            ++*dropped;
            continue;
        }
        PrimRef r;
        r.box = bounds(t);
        r.centroid = r.box.center();
        r.id = static_cast<std::uint32_t>(i);
        refs.push_back(r);
    }
    if (refs.size() >= (std::size_t{1} << 31))
        throw Error(cat("scene has ", refs.size(), " triangles; at most 2^31 are supported"));
    return refs;
}

RangeBounds rangeBounds(const PrimRef* refs, std::size_t n)
{
    RangeBounds b;
    for (std::size_t i = 0; i < n; ++i) {
        b.box.grow(refs[i].box);
        b.centroids.grow(refs[i].centroid);
    }
    return b;
}

class BinnedBuilder {
public:
    BinnedBuilder(std::vector<PrimRef>& refs, const BuildOptions& opt)
        : refs_(refs), opt_(opt), bins_(std::clamp(opt.bins, 2, kMaxBins))
    {
        threads_ = opt.threads > 0 ? opt.threads
                                   : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
        nodes_.resize(std::max<std::size_t>(1, 2 * refs.size()));
    }

    BinaryBvh run()
    {
        BinaryBvh out;
        if (refs_.empty())
            return out;
        nodeCount_ = 1;
        const RangeBounds rb = parallelBounds(0, static_cast<std::uint32_t>(refs_.size()));
        build(0, 0, static_cast<std::uint32_t>(refs_.size()), rb, 0);
        nodes_.resize(nodeCount_.load());
        out.nodes = std::move(nodes_);
        out.primOrder.resize(refs_.size());
        for (std::size_t i = 0; i < refs_.size(); ++i)
            out.primOrder[i] = refs_[i].id;
        out.depth = maxDepth_.load();
        return out;
    }

private:
    static constexpr int kMaxBins = 64;
    static constexpr std::uint32_t kParallelBinning = 1u << 15;   // refs, for chunked binning
    static constexpr std::uint32_t kParallelSubtree = 1u << 12;  // refs, to fork a subtree

    struct Bins {
        std::array<std::array<Aabb, kMaxBins>, 3> box;
        std::array<std::array<std::uint32_t, kMaxBins>, 3> count{};
    };

    float blocks(std::uint32_t n) const { return packetCost(n, opt_); }

    int binOf(const glm::vec3& c, int axis, const Aabb& cb, float scale) const
    {
        const int b = static_cast<int>((c[axis] - cb.lo[axis]) * scale);
        return std::clamp(b, 0, bins_ - 1);
    }

    glm::vec3 binScale(const Aabb& cb) const
    {
        glm::vec3 s;
        for (int a = 0; a < 3; ++a) {
            const float e = cb.hi[a] - cb.lo[a];
            s[a] = e > 0.0f ? static_cast<float>(bins_) * (1.0f - 1e-6f) / e : 0.0f;
        }
        return s;
    }

    void binRange(std::uint32_t begin, std::uint32_t end, const Aabb& cb, const glm::vec3& scale,
                  Bins& bins) const
    {
        for (std::uint32_t i = begin; i < end; ++i) {
            const PrimRef& r = refs_[i];
            for (int a = 0; a < 3; ++a) {
                if (scale[a] == 0.0f)
                    continue;
                const int b = binOf(r.centroid, a, cb, scale[a]);
                bins.box[a][b].grow(r.box);
                bins.count[a][b] += 1;
            }
        }
    }

    template <class F>
    void forChunks(std::uint32_t begin, std::uint32_t end, F&& f) const
    {
        const std::uint32_t n = end - begin;
        const int chunks = std::max(1, std::min<int>(threads_, static_cast<int>(n / 4096)));
        std::vector<std::future<void>> jobs;
        for (int c = 1; c < chunks; ++c) {
            const std::uint32_t b = begin + static_cast<std::uint32_t>(std::uint64_t(n) * c / chunks);
            const std::uint32_t e = begin + static_cast<std::uint32_t>(std::uint64_t(n) * (c + 1) / chunks);
            jobs.push_back(std::async(std::launch::async, [&f, b, e, c] { f(b, e, c); }));
        }
        f(begin, begin + static_cast<std::uint32_t>(std::uint64_t(n) / chunks), 0);
        for (auto& j : jobs)
            j.get();
    }

    RangeBounds parallelBounds(std::uint32_t begin, std::uint32_t end) const
    {
        if (end - begin < kParallelBinning)
            return rangeBounds(refs_.data() + begin, end - begin);
        std::vector<RangeBounds> part(static_cast<std::size_t>(threads_));
        forChunks(begin, end, [&](std::uint32_t b, std::uint32_t e, int c) {
            part[static_cast<std::size_t>(c)] = rangeBounds(refs_.data() + b, e - b);
        });
        RangeBounds all;
        for (const auto& p : part) {
            all.box.grow(p.box);
            all.centroids.grow(p.centroids);
        }
        return all;
    }

    void computeBins(std::uint32_t begin, std::uint32_t end, const Aabb& cb, const glm::vec3& scale,
                     Bins& bins) const
    {
        if (end - begin < kParallelBinning) {
            binRange(begin, end, cb, scale, bins);
            return;
        }
        std::vector<Bins> part(static_cast<std::size_t>(threads_));
        forChunks(begin, end, [&](std::uint32_t b, std::uint32_t e, int c) {
            binRange(b, e, cb, scale, part[static_cast<std::size_t>(c)]);
        });
        for (const auto& p : part)
            for (int a = 0; a < 3; ++a)
                for (int i = 0; i < bins_; ++i) {
                    bins.box[a][i].grow(p.box[a][i]);
                    bins.count[a][i] += p.count[a][i];
                }
    }

    // Best SAH split: returns false when binning cannot separate the centroids.
    bool findSplit(std::uint32_t begin, std::uint32_t end, const RangeBounds& rb, int* axisOut,
                   int* binOut, float* costOut) const
    {
        const glm::vec3 scale = binScale(rb.centroids);
        if (scale == glm::vec3(0.0f))
            return false;
        Bins bins;
        computeBins(begin, end, rb.centroids, scale, bins);
        float best = std::numeric_limits<float>::infinity();
        for (int a = 0; a < 3; ++a) {
            if (scale[a] == 0.0f)
                continue;
            std::array<float, kMaxBins> rightCost{};
            Aabb acc;
            std::uint32_t cnt = 0;
            for (int i = bins_ - 1; i > 0; --i) {
                acc.grow(bins.box[a][i]);
                cnt += bins.count[a][i];
                rightCost[i] = acc.halfArea() * blocks(cnt);
            }
            acc = Aabb();
            cnt = 0;
            for (int i = 1; i < bins_; ++i) {
                acc.grow(bins.box[a][i - 1]);
                cnt += bins.count[a][i - 1];
                const std::uint32_t right = (end - begin) - cnt;
                if (cnt == 0 || right == 0)
                    continue;
                const float c = acc.halfArea() * blocks(cnt) + rightCost[i];
                if (c < best) {
                    best = c;
                    *axisOut = a;
                    *binOut = i;
                }
            }
        }
        if (!(best < std::numeric_limits<float>::infinity()))
            return false;
        const float area = rb.box.halfArea();
        *costOut = opt_.traversalCost + (area > 0.0f ? best / area : best);
        return true;
    }

    void makeLeaf(std::uint32_t node, std::uint32_t begin, std::uint32_t end, const Aabb& box,
                  int depth)
    {
        nodes_[node].box = box;
        nodes_[node].first = begin;
        nodes_[node].count = end - begin;
        int d = maxDepth_.load();
        while (depth > d && !maxDepth_.compare_exchange_weak(d, depth)) {
        }
    }

    void build(std::uint32_t node, std::uint32_t begin, std::uint32_t end, const RangeBounds& rb,
               int depth)
    {
        const std::uint32_t n = end - begin;
        const float leafCost = blocks(n);
        std::uint32_t mid = begin;
        bool split = false;
        if (n > 1 && depth < opt_.maxSahDepth) {
            int axis = 0, bin = 0;
            float cost = 0.0f;
            if (findSplit(begin, end, rb, &axis, &bin, &cost) &&
                (n > static_cast<std::uint32_t>(opt_.maxLeafSize) || cost < leafCost)) {
                const float scale = binScale(rb.centroids)[axis];
                const Aabb cb = rb.centroids;
                auto it = std::partition(refs_.begin() + begin, refs_.begin() + end,
                                         [&](const PrimRef& r) {
                                             return binOf(r.centroid, axis, cb, scale) < bin;
                                         });
                mid = static_cast<std::uint32_t>(it - refs_.begin());
                split = mid > begin && mid < end;
            }
        }
        if (!split) {
            if (n <= static_cast<std::uint32_t>(opt_.maxLeafSize)) {
                makeLeaf(node, begin, end, rb.box, depth);
                return;
            }
            // Centroids that binning cannot separate, or too deep for SAH: split at the median of
            // the longest centroid axis (halves the range, so depth grows by log2 at most).
            mid = begin + n / 2;
            const int axis = rb.centroids.longestAxis();
            std::nth_element(refs_.begin() + begin, refs_.begin() + mid, refs_.begin() + end,
                             [axis](const PrimRef& a, const PrimRef& b) {
                                 return a.centroid[axis] < b.centroid[axis];
                             });
        }
        const std::uint32_t left = nodeCount_.fetch_add(2);
        nodes_[node].box = rb.box;
        nodes_[node].first = left;
        nodes_[node].count = 0;
        const RangeBounds lb = parallelBounds(begin, mid);
        const RangeBounds rbRight = parallelBounds(mid, end);
        if (n >= kParallelSubtree && busy_.fetch_add(1) < threads_ - 1) {
            auto job = std::async(std::launch::async, [&, left, begin, mid, lb, depth] {
                build(left, begin, mid, lb, depth + 1);
            });
            build(left + 1, mid, end, rbRight, depth + 1);
            job.get();
            busy_.fetch_sub(1);
        } else {
            if (n >= kParallelSubtree)
                busy_.fetch_sub(1);
            build(left, begin, mid, lb, depth + 1);
            build(left + 1, mid, end, rbRight, depth + 1);
        }
    }

    std::vector<PrimRef>& refs_;
    const BuildOptions& opt_;
    int bins_;
    int threads_ = 1;
    std::vector<BinaryNode> nodes_;
    std::atomic<std::uint32_t> nodeCount_{0};
    std::atomic<int> maxDepth_{0};
    std::atomic<int> busy_{0};
};

// Full sweep: every boundary between sorted centroids on every axis.
class SweepBuilder {
public:
    SweepBuilder(std::vector<PrimRef>& refs, const BuildOptions& opt) : refs_(refs), opt_(opt) {}

    BinaryBvh run()
    {
        BinaryBvh out;
        if (refs_.empty())
            return out;
        nodes_.reserve(2 * refs_.size());
        nodes_.emplace_back();
        build(0, 0, static_cast<std::uint32_t>(refs_.size()), 0);
        out.nodes = std::move(nodes_);
        for (const auto& r : refs_)
            out.primOrder.push_back(r.id);
        out.depth = depth_;
        return out;
    }

private:
    void build(std::uint32_t node, std::uint32_t begin, std::uint32_t end, int depth)
    {
        const std::uint32_t n = end - begin;
        const RangeBounds rb = rangeBounds(refs_.data() + begin, n);
        float best = std::numeric_limits<float>::infinity();
        int bestAxis = -1;
        std::uint32_t bestMid = 0;
        std::vector<float> right(n + 1);
        for (int a = 0; a < 3 && n > 1; ++a) {
            std::sort(refs_.begin() + begin, refs_.begin() + end,
                      [a](const PrimRef& x, const PrimRef& y) {
                          return x.centroid[a] < y.centroid[a] ||
                                 (x.centroid[a] == y.centroid[a] && x.id < y.id);
                      });
            Aabb acc;
            for (std::uint32_t i = n; i > 0; --i) {
                acc.grow(refs_[begin + i - 1].box);
                right[i - 1] = acc.halfArea() * packetCost(n - (i - 1), opt_);
            }
            acc = Aabb();
            for (std::uint32_t i = 1; i < n; ++i) {
                acc.grow(refs_[begin + i - 1].box);
                const float c = acc.halfArea() * packetCost(i, opt_) + right[i];
                if (c < best) {
                    best = c;
                    bestAxis = a;
                    bestMid = begin + i;
                }
            }
        }
        const float area = rb.box.halfArea();
        const float cost = opt_.traversalCost + (area > 0.0f ? best / area : best);
        const bool leaf = n == 1 ||
                          (n <= static_cast<std::uint32_t>(opt_.maxLeafSize) &&
                           cost >= packetCost(n, opt_));
        nodes_[node].box = rb.box;
        if (leaf) {
            nodes_[node].first = begin;
            nodes_[node].count = n;
            depth_ = std::max(depth_, depth);
            return;
        }
        const int a = bestAxis;
        std::sort(refs_.begin() + begin, refs_.begin() + end,
                  [a](const PrimRef& x, const PrimRef& y) {
                      return x.centroid[a] < y.centroid[a] ||
                             (x.centroid[a] == y.centroid[a] && x.id < y.id);
                  });
        const std::uint32_t left = static_cast<std::uint32_t>(nodes_.size());
        nodes_[node].first = left;
        nodes_[node].count = 0;
        nodes_.emplace_back();
        nodes_.emplace_back();
        build(left, begin, bestMid, depth + 1);
        build(left + 1, bestMid, end, depth + 1);
    }

    std::vector<PrimRef>& refs_;
    const BuildOptions& opt_;
    std::vector<BinaryNode> nodes_;
    int depth_ = 0;
};

template <class Builder>
BinaryBvh buildWith(const std::vector<Triangle>& tris, const BuildOptions& opt)
{
    const auto t0 = std::chrono::steady_clock::now();
    std::size_t dropped = 0;
    std::vector<PrimRef> refs = makeRefs(tris, &dropped);
    BinaryBvh bvh = Builder(refs, opt).run();
    bvh.droppedDegenerate = dropped;
    bvh.buildSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return bvh;
}

}  // namespace

BinaryBvh buildBinnedSah(const std::vector<Triangle>& tris, const BuildOptions& opt)
{
    return buildWith<BinnedBuilder>(tris, opt);
}

BinaryBvh buildSweepSah(const std::vector<Triangle>& tris, const BuildOptions& opt)
{
    return buildWith<SweepBuilder>(tris, opt);
}

double sahCost(const BinaryBvh& bvh, const BuildOptions& opt)
{
    if (bvh.nodes.empty())
        return 0.0;
    const double root = bvh.nodes[0].box.halfArea();
    double cost = 0.0;
    for (const auto& n : bvh.nodes) {
        const double a = root > 0.0 ? n.box.halfArea() / root : 1.0;
        cost += n.isLeaf() ? a * packetCost(n.count, opt) : a * opt.traversalCost;
    }
    return cost;
}

}  // namespace fen
