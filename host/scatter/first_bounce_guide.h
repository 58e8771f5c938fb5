// first_bounce_guide.h — the first-bounce guide's tables, statistics and learning on the host
// (DESIGN.md §3.4; device half: kernels/lib/guide.h, layout: kernels/shared/fen_guide.h). A
// scattering feature -- it steers a path's first diffuse bounce, in shade.cl -- so it lives with
// the scattering code; the adaptive strategy owns one and learns it on its passes.
//
// Light that must bounce off something outside before it can enter (the ground in front of a
// window, a sunlit wall across a courtyard) is what emission alone cannot steer: the emitted ray
// only decides where the bounce happens, the bounce decides whether the light gets in.
//
// Directions. The guide learns, per slot, which leaves of a quadtree over the cosine hemisphere's
// square send a unit of weight to the camera, and the device draws the first bounce from that:
// leaf b has probability P(b) = (1 - share) m(b) / sum m + share A(b), density d(b) = P(b) / A(b),
// with A(b) its area, m(b) = sqrt(S(b) A(b)) and S(b) the leaf's learned integral of the squared
// delivery -- the piecewise-constant density that minimises the second moment sum S(b) / d(b) of
// what a unit of weight delivers (for a delivery that is the same for every path through a leaf,
// the first moment: the zero-variance density). It is the one-sample mixture of the cosine, which
// draws leaf b with probability A(b), and the learned density, with weight `share` on the cosine:
// share > 0 keeps every leaf drawable, the weights finite and the image unbiased. A slot is
// guided only when its statistics predict that the table cuts that second moment at least
// minGain times against the cosine's (sum S / sum S/d). The mixture never predicts a cut below 1
// (up to the table's rounding), so the default (1) steers every slot that has seen enough: a gate
// of 2 left unguided the slots whose rare entries through a window were the house's fireflies
// (options below).
//
// Resolution that follows the light, in the slots whose tables steer. The trees start at 8 x 8
// leaves; after each pass a leaf that held more than splitShare of its slot's m in that pass, with
// at least minLeafConnections contributions there, becomes four, each inheriting a quarter of its
// totals, down to maxDepth -- as practical path guiding's directional quadtrees, so that a window of
// a few thousandths of a steradian seen from far away gets leaves of its own. The slots are six per
// spatial leaf (the side a vertex's normal faces most); the spatial leaves start as a lattice of
// voxels over the scene's bounding cube, and one whose slots gathered spatialSplitConnections
// contributions in a pass is halved (x, y, z in turn, down to maxSpatialDepth), both halves
// starting from its trees with half their totals.
//
// Bounded memory. Everything lives in buffers sized at construction (memoryMiB), whatever the
// image size; when a pass's splits would pass them, the largest go first and the rest wait
// (reported).
//
// Learning runs on the owner's passes (the adaptive strategy's): learn() reads the pass's
// statistics, adds them to the totals (each sample's square times the density it was drawn with,
// so passes drawn from different tables add up), refines the trees, rebuilds every slot's table,
// uploads the used part of each section and clears the statistics. Deterministic: the statistics
// are integer sums and every choice is ordered, so the trees after a pass depend only on the seed
// and the path counts. The per-slot work runs in shares over the host's threads (util/in_shares.h),
// each slot writing only its own results, so the bytes are the same at any thread count: a GPU
// waits while the host learns (docs/results/gpu.md, run 4). Off (enabled = false):
// GuideParams.slots = 0 and small placeholder buffers; the kernels then scatter exactly as
// without a guide.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "team/summed_buffer.h"

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "cl/context.h"
#include "shared/fen_guide.h"

namespace fen {

class StateReader;
class StateWriter;

struct GuideOptions {
    // On by default: over seven interleaved seeds at equal time it made adaptive 2.5x more
    // efficient on the courtyard, 1.9x under snow, 1.2x in the room, and 0.95-1.1x on the bay
    // window and the house (docs/results/guide.md, "Seven seeds").
    bool enabled = true;
    double share = 0.25;              // the uniform table's share in every learned one
    double minConnections = 32.0;     // contributions a slot needs before it is learned
    // ... and the second-moment cut its table must promise. 1: every slot that has seen enough
    // steers (a learned mixture never promises a cut below 1). It was 2; at equal time 1
    // made the house 1.18x as efficient (fifteen seeds): a fifth of the house's variance came from
    // the rare paths that got in through a window after a bounce in slots the gate left unguided,
    // 3 % of its light (docs/results/guiding.md, "Every slot that has seen enough steers").
    double minGain = 1.0;
    // Lattice: voxels across the scene's bounding sphere's radius (the cube of side 2R then has
    // the next power of 2 >= 2 voxelsAcross voxels a side). Coarse on purpose: a slot must gather
    // contributions before it is steered, and far from the camera they are rare (R/4 beat R/32 on
    // all six measured scenes: docs/results/guide.md); the spatial splits refine it where they
    // are not.
    int voxelsAcross = 4;
    // A spatial leaf whose six slots gathered this many contributions in a pass is halved (along
    // x, y, z in turn), down to maxSpatialDepth halvings below its voxel.
    double spatialSplitConnections = 4096.0;
    int maxSpatialDepth = 9;
    int maxDepth = FEN_GUIDE_MAX_DEPTH;  // leaves down to 2^-maxDepth of the square's side (3: 8 x 8)
    double splitShare = 0.02;         // a leaf holding more of its slot's m than this is split ...
    double minLeafConnections = 8.0;  // ... once it has seen this many contributions
    double memoryMiB = 256.0;         // device memory for the trees and their statistics
    // Draw from the tables at every diffuse vertex whose slot is learned, not only at a path's
    // first (the importance a table learned belongs to the place and the direction, whichever
    // bounce reaches them). Off by default: at equal time it lost on the house, the courtyard and
    // the snow house -- paths steered into view bounce more and each guided vertex costs a table
    // draw, more than the variance it saves (docs/results/guiding.md, "Every vertex").
    bool everyVertex = false;
    // Weight windows (roulette and splitting from the learned adjoint): at a path's first diffuse
    // vertex, the ratio of its weight Y(beta) to its slot's window weight w -- with rule Mean, the
    // weight whose expected contribution from there on is the target (the mean over all paths);
    // with rule Moment, the weight whose root second moment of contributions is the target's (the
    // root mean square over all paths) -- decides: a ratio of 2 or more splits the path into
    // min(floor(ratio), windowSplitMax) branches; one below 1/2 survives with probability
    // max(ratio, windowMinSurvival), its weight over that. Learned on the guide's passes; a slot
    // with fewer than windowMinVisits visits has no window (the fixed rules apply there). On by
    // default with rule Moment, splitting only: measured at equal time on every shipped scene, it
    // gained or held (docs/results/guiding.md, "Weight windows").
    enum class WindowRule { Mean, Moment };
    bool window = true;
    WindowRule windowRule = WindowRule::Moment;
    int windowSplitMax = 16;
    double windowMinSurvival = 1.0;  // 1: never culled (culling lost where measured: docs/results/guiding.md)
    // Past the first vertex too: a path not split yet splits at any later diffuse vertex whose
    // slot's window its weight passes twice over (culling stays at the first vertex). Light that
    // bounced outside before it got in is heavy only once it is in, after the first vertex; on by
    // default: at equal time it made the house 1.6x, the snow house 1.6x, the courtyard 1.2x and
    // the inner room 1.3x as efficient, the bay window level and the room 0.97-1.01x
    // (docs/results/guiding.md, "Windows past the first vertex").
    bool windowEveryVertex = true;
    // ... where the ratio of its weight to the slot's window counts windowLater times over: the
    // windows, learned at first vertices, are that much lower past them. 4 by default: at equal
    // time it made the house 1.22x and the snow house 1.33x as efficient as 1 (the first vertex's
    // windows; nine seeds each), the courtyard 1.08x and the inner room 1.12x, and cost the room
    // 7 % and the bay window 11 %, lit straight through their glass (docs/results/guiding.md,
    // "Lower windows past the first vertex").
    double windowLater = 4.0;
    double windowMinVisits = 256.0;
    // With weight windows, also sum the opening aim's share statistics (fen_guide.h
    // FEN_GUIDE_MIXED_SQ_LO) in each slot's window sums, for the aim to learn its share from
    // (passAimSums(); set by the strategy, which owns the aim).
    bool aimSums = false;
    // No guide: placeholders bound where a strategy has none (GuideParams.slots = 0).
    static GuideOptions off()
    {
        GuideOptions o;
        o.enabled = false;
        o.window = false;
        return o;
    }
};
// Throws a one-line error naming the option for a value out of range.
void validateGuideOptions(const GuideOptions& o);

class FirstBounceGuide {
public:
    // The lattice covers the sphere (centre, radius_m) at radius_m / voxelsAcross per voxel.
    FirstBounceGuide(ocl::Context& ctx, const GuideOptions& o, glm::dvec3 centre, double radius_m);
    bool enabled() const { return opt_.enabled; }
    const cl::Buffer& params() const { return params_; }
    const cl::Buffer& tables() const { return tables_; }
    const cl::Buffer& stats() const { return stats_; }
    const cl::Buffer& windowStats() const { return windowStats_; }  // with weight windows (fen_guide.h)
    // The statistics as a team sums them (team/shared_sums.h): per leaf, a 128-bit sum and a count;
    // and the weight windows' per slot, two 128-bit sums and a count (none without windows).
    SummedBuffer summed() const { return {&stats_, opt_.enabled ? leafCount_ : 0, {2, 1}}; }
    SummedBuffer windowSummed() const { return {&windowStats_, deviceParams_.windows_at ? trees_.size() : 0, {2, 2, 1, 2, 2}}; }
    // The opening aim's share statistics of the pass learn() last read, over every slot (with
    // aimSums; else zeros): the squares of what paths that left a first vertex by the aim's mixture
    // delivered (mixed), and of those that left in the aim's region (aimed), at the window
    // statistics' scale squared.
    struct AimSums {
        double mixed = 0.0, aimed = 0.0;
    };
    AimSums passAimSums() const { return passAimSums_; }
    std::size_t deviceBytes() const { return deviceBytes_; }

    // After a pass: statistics into the totals, trees refined, new tables up, statistics cleared.
    void learn();
    // Clears the device statistics (a resumed render starts between passes).
    void clearStats();

    // For tests and reports: a slot's leaves, in the order of their global indices.
    struct LeafView {
        double x0, y0, size;   // the leaf's square in the unit square
        double probability;    // the realised probability the device draws it with (guided slots)
        std::uint32_t index;   // its global index: the key of its statistics
    };
    std::vector<LeafView> leaves(std::uint32_t slot) const;
    std::size_t slotCount() const { return trees_.size(); }
    std::size_t spatialLeaves() const { return spatialLeaves_.size(); }
    bool learned(std::uint32_t slot) const { return trees_.at(slot).learned; }
    std::uint32_t learnedSlots() const { return learnedSlots_; }
    std::size_t leafCount() const { return leafCount_; }
    std::size_t leafCapacity() const { return leafCapacity_; }

    void save(StateWriter& w) const;
    void load(StateReader& r);
    nlohmann::json report() const;

private:
    // A slot's tree: nodes with four children each (>= 0: a node, < 0: leaf ~c), node 0 the root.
    struct Leaf {
        double sumSq = 0.0, connections = 0.0;  // S(b) and contributions, over all passes
        // Every total above, in the order a checkpoint keeps them (save(), load()).
        std::array<double*, 2> totals() { return {&sumSq, &connections}; }
        std::array<double, 2> totals() const { return {sumSq, connections}; }
        void scaleTotals(double f)
        {
            for (double* v : totals())
                *v *= f;
        }
        float density = 1.0f;                   // d(b) the last tables drew it with (1: the cosine)
        std::uint32_t x0 = 0, y0 = 0, depth = 0;  // corner in 2^-FEN_GUIDE_MAX_DEPTH units
        double area() const { return std::ldexp(1.0, -2 * static_cast<int>(depth)); }
    };
    // With weight windows, a slot's totals over all passes: the luminance delivered after leaving a
    // first vertex there, the weight's luminance over A_pix as it arrived, each to the rule's power,
    // and how many left (fen_guide.h).
    struct WindowTotals {
        double delivered = 0.0, arrived = 0.0, visits = 0.0;
        // Every total above, in the order a checkpoint keeps them (save(), load()).
        std::array<double*, 3> totals() { return {&delivered, &arrived, &visits}; }
        std::array<double, 3> totals() const { return {delivered, arrived, visits}; }
        void scale(double f)
        {
            for (double* v : totals())
                *v *= f;
        }
    };
    struct Tree {
        std::vector<std::array<std::int32_t, 4>> nodes;
        std::vector<Leaf> leaves;
        WindowTotals window;  // the slot's, whatever its leaves
        std::vector<std::uint32_t> alias;  // the learned table's columns (threshold, alias)
        std::uint32_t aliasShift = 31;
        bool learned = false;
    };
    // A spatial leaf: where it hangs (a voxel's word, or a node's lower or upper child) and how many
    // halvings below its voxel it is.
    struct SpatialLeaf {
        std::uint32_t voxel = 0;           // its voxel (for reports and checks)
        std::int64_t node = -1;            // -1: the voxel's own word; else the spatial node ...
        std::uint32_t half = 0;            // ... and which child (0 lower, 1 upper)
        std::uint32_t depth = 0;
    };
    static Leaf quadrant(std::uint32_t x0, std::uint32_t y0, std::uint32_t depth, std::uint32_t q);
    static Tree initialTree();
    static bool isInitial(const Tree& t);  // the full tree of depth FEN_GUIDE_INITIAL_DEPTH
    // One pass's statistics as read: leaf i of slot s at first[s] + i (its S and contributions).
    struct PassStats {
        std::vector<std::size_t> first;
        std::vector<double> sumSq, connections;
    };
    std::size_t refine(const PassStats& pass);
    static void splitLeaves(Tree& tree, const std::vector<char>& split);
    std::size_t refineSpace(const std::vector<double>& passConnections);
    std::size_t nodeCount() const;
    std::vector<double> mixture(const Tree& t) const;
    bool steers(const Tree& t, const std::vector<double>& p) const;
    std::vector<std::uint64_t> spaceShape() const;
    void rebuild();
    void rebuildWindows();
    void upload();
    ocl::Context& ctx_;
    GuideOptions opt_;
    dev::GuideParams deviceParams_{};
    std::vector<Tree> trees_;                      // per slot: FEN_GUIDE_SIDES per spatial leaf
    std::uint32_t cells_ = 1;                      // voxels along each side of the lattice cube
    double side_m_ = 0.0;                          // the cube's side
    std::vector<std::uint32_t> voxelWord_;         // per voxel: FEN_GUIDE_LEAF | spatial leaf, or a node
    std::vector<std::array<std::uint32_t, 2>> spatialNodes_;
    std::vector<SpatialLeaf> spatialLeaves_;
    std::size_t slotCapacity_ = 0, spatialCapacity_ = 0, lastSpatialSplits_ = 0, deferredSpatialSplits_ = 0;
    std::vector<char> promising_;                  // per slot, after refine(): its table will steer
    std::size_t leafCapacity_ = 0, nodeCapacity_ = 0, columnCapacity_ = 0;
    std::size_t leafCount_ = 0, deferredSplits_ = 0, lastSplits_ = 0;
    // The tables' sections as uploaded (fen_guide.h), each as long as it is used.
    std::vector<std::uint32_t> records_, spatialWords_, nodeWords_, leafWords_, columnWords_, windowWords_,
        leafSlotWords_;
    std::size_t windowSlots_ = 0;  // slots with a window, after rebuild()
    AimSums passAimSums_;
    double windowTarget_ = 0.0;    // T, in units of the delivered statistic, after rebuild()
    std::uint32_t learnedSlots_ = 0, candidateSlots_ = 0, maxDepthSeen_ = 0;
    double learnSeconds_ = 0.0, lastLearnSeconds_ = 0.0;
    // learn()'s scratch, kept between passes only so that each pass writes into memory already
    // mapped: fresh, a pass's read-back of 514,464 leaves took more page faults than reading.
    std::vector<std::uint64_t> statsRead_, windowRead_;
    PassStats pass_;
    cl::Buffer params_, tables_, stats_, windowStats_;
    std::size_t deviceBytes_ = 0;
};

}  // namespace fen
