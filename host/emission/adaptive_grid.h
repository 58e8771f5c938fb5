// adaptive_grid.h — the learned emission density of the `adaptive` strategy (DESIGN.md §3.3, the
// paper's eq. 7), on the host; no OpenCL here, so it is tested on its own.
//
// A cell is a set of emitted rays: a box of directions (the sun's cone, or a box of (s, t) over
// the sky: cos(theta) = 1 - s, phi = 2 pi t, equal areas equal solid angles) times a box of the 2D
// parametrisation of the origin in a region (the emission disk, or a portal plane's frame). Paths
// pick a cell with probability P(cell) and then sample the base density restricted to it
// (directions uniform in solid angle, origins uniform in the box), so a path's weight is its base
// weight times P_base(cell) / P(cell).
//
// What is learned. Write Lambda for a contribution's luminance had its path been emitted with the
// base density (Lambda = C P(c) / P_base(c), C the contribution as rendered). The variance of the
// image, summed over pixels, is sum_c P_base(c)^2 <sum Lambda^2>_c / P(c) - const, smallest for
// P(c) proportional to P_base(c) sqrt(<sum Lambda^2>_c) -- eq. 7 written per cell. <sum Lambda^2>
// does not depend on how paths were emitted, so every pass's statistics add up.
// Estimating <sum Lambda^2> (measured: docs/results/adaptive.md), per sixteenth of a cell (each
// quarter of its origin box times each quarter of its direction box):
//   - `squares`: the sample mean of sum Lambda^2 over the part's paths -- eq. 7 taken literally. A
//     light tracer's contributions are heavy-tailed (a path that happens to hit a wall next to the
//     camera deposits 1 / d^2 more), so this is dominated by a few events and swings by orders of
//     magnitude between neighbours;
//   - `pooled`: only the first moment S1 = sum Lambda, the paths n and the contributions c, and
//     <sum Lambda^2> ~ g S1^2 / (n c) -- exact when the part's contributions are equal, with the
//     spread factor g taken as common to all cells (it is mostly the camera's geometry, the same
//     for every path that reaches a room), so it cancels in P. The sum of Lambda converges where
//     the sum of squares does not;
//   - `larger` (the default): the larger of the two, max(g S1^2 / (n c), squares), g now the
//     spread over all visited cells (sum of P_base squares / sum of P_base pooled figures, each
//     per path). A cell whose light comes as rare large contributions -- most of its paths miss,
//     a few get in and bounce on as fireflies -- has a spread far above the common one, and the
//     pooled figure understates it by that much; an understated cell is drawn too rarely and its
//     paths weigh too much, an overstated one only dilutes the others. So a cell is raised to its
//     squares where they exceed its share of the common spread, and otherwise keeps the pooled
//     figure's stability. Where every cell's contributions are even, both agree and g = 1.
//     Measured: docs/results/guiding.md, "Cells judged by the larger estimate".
// A cell's second moment is the mean of its parts', so a cell whose light is uneven (an opening's
// edge) is not judged by a pooled figure that its dim parts dilute.
// What the paper leaves open, decided here:
//   - prior: each cell starts with k = 32 pseudo-paths (2 per part) carrying the base-weighted mean
//     of the visited cells: an unvisited cell gets the share of an average cell, and one whose n
//     paths carried nothing decays like sqrt(k / n) -- never to 0. (k = 1 let a cell that had
//     not yet seen its rare light fall so low that the light, when it came, came as fireflies:
//     docs/results/adaptive.md);
//   - defensive share: P = (1 - alpha) P_learned + alpha P_base, so every cell where the base
//     density has light keeps at least alpha of its base probability (no cell can die);
//   - resolution: a cell is split in four -- along its origin box or along its direction box,
//     whichever lowers the learned objective sum_c P_base(c) sqrt(<sum Lambda^2>_c) (the square
//     root of the variance at the optimum) more -- when that lowers it by at least `splitGain` of
//     it and the cell has seen `minConnectionsToSplit` contributions: where the light varies
//     inside it, an opening's edge, or directions whose openings project to different places. Down
//     to `maxDepth` (origin) and `maxSkyDepth` (direction), up to `maxCells` cells. Each child
//     starts with its parts' statistics.
// Invariants: probabilities are positive for every cell with P_base > 0 and sum to 1; the state
// after update() depends only on the statistics added, so it is deterministic.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

namespace fen {

class StateReader;
class StateWriter;

struct GridCell {
    bool sun = false;          // directions: the sun's cone, else the sky box below
    std::uint32_t region = 0;  // 0: the emission disk; 1 + g: portal plane g
    std::uint32_t depth = 0;   // origin box: [ix, ix + 1) x [iy, iy + 1) times 2^-depth
    std::uint32_t ix = 0, iy = 0;
    std::uint32_t skyDepth = 0;  // direction box: [is, is + 1) x [it, it + 1) times 2^-skyDepth of (s, t);
                                 // is >= 2^skyDepth: s in [1, 2), the ground's glow below the horizon
    std::uint32_t is = 0, it = 0;
    double base = 0.0;         // P_base(cell)
    struct Stats {
        double sum = 0.0;          // sum of Lambda over its contributions
        double sumSq = 0.0;        // sum of Lambda^2 over its contributions
        double paths = 0.0;        // paths drawn from it, rejected candidates included
        double connections = 0.0;  // contributions that reached the camera
        void add(const Stats& o);
        void scale(double f);
    };
    Stats part[16];            // by 4 * direction quarter + origin quarter (bit 0/2: upper half in x/s)
    double prob = 0.0;         // P(cell) now
    Stats total() const;
    double boxArea() const;    // 4^-depth
    double skyArea() const;    // 4^-skyDepth of the (s, t) square
};

enum class GridEstimate { Pooled, Squares, Larger };

struct GridLearning {
    GridEstimate estimate = GridEstimate::Larger;
    double defensive = 0.1;           // alpha
    double splitGain = 1.0 / 2048.0;  // of the objective
    std::uint32_t maxDepth = 10;
    std::uint32_t maxSkyDepth = 6;
    std::uint32_t maxCells = 1u << 15;
    double priorPaths = 32.0;         // the prior weighs as much as this many paths
    double minConnectionsToSplit = 8.0;
    std::uint32_t skyRoots = 1;       // (s, t) unit squares of sky directions: 1 the sky's, 2 with the ground's
};

class AdaptiveGrid {
public:
    // The share of a cell's base probability that each quarter of its direction box holds (four
    // numbers summing to 1, direction quarters in the order of GridCell::part): the base density
    // over directions (the sky's flux, weighted for a portal plane) is not uniform in solid angle.
    using SkySplit = std::function<void(const GridCell& cell, double share[4])>;

    // `cells` with their boxes and base set; base probabilities must sum to 1.
    AdaptiveGrid(std::vector<GridCell> cells, const GridLearning& learning, SkySplit skySplit);

    const std::vector<GridCell>& cells() const { return cells_; }
    // One pass's statistics, per part of every current cell (16 i + part): Lambda sums are the
    // device's sums of contribution luminances times P(cell) / P_base(cell), and of their squares
    // times its square.
    void addPass(const std::vector<GridCell::Stats>& parts);
    // New probabilities from all statistics so far; splits cells where that pays. Returns the
    // number of cells split.
    std::size_t update();
    // The learned share (before the defensive mix) of every cell, as update() last computed it.
    const std::vector<double>& learned() const { return learned_; }
    // The variance per path (summed over pixels, up to a factor common to all densities) that
    // drawing cells with probabilities `prob` would have, by the statistics so far: the sum of
    // (P_base sqrt(<sum Lambda^2>))^2 / P over the cells. Relative figures of it weigh batches.
    double predictedVariance(const std::vector<double>& prob);
    // Sets P(cell) directly (normalised; every cell with P_base > 0 must get P > 0).
    void setProbabilities(const std::vector<double>& p);
    // A hash of the cells and their probabilities: equal grids, equal checksums.
    std::uint64_t checksum() const;
    double paths() const { return totalPaths_; }
    double connections() const { return totalConnections_; }
    std::uint32_t deepest() const;
    std::uint32_t deepestSky() const;
    // Everything the grid has learned, for a checkpoint (render/checkpoint.h); load() checks what
    // it reads against the learning limits and `regions` (fen::Error naming the key).
    void save(StateWriter& w) const;
    void load(StateReader& r, std::uint32_t regions);

private:
    // <sum Lambda^2> of statistics s with priorPaths pseudo-paths of the prior.
    double secondMoment(const GridCell::Stats& s, double priorPaths) const;
    // P_base sqrt(<sum Lambda^2>) of a set of parts of a cell holding `baseShare` of its base.
    double value(const GridCell& c, const int* parts, int n, double baseShare) const;
    double estimate(const GridCell& c) const;
    void computePrior();
    void computeLearned();
    std::vector<GridCell> cells_;
    std::vector<double> learned_;
    GridLearning learning_;
    SkySplit skySplit_;
    double priorFirst_ = 0.0, priorRate_ = 0.0, priorSecond_ = 0.0;  // per base path
    double spread_ = 1.0;  // g: the squares over the pooled figures, over all visited cells
    bool seen_ = false;
    double totalPaths_ = 0.0, totalConnections_ = 0.0;
};

}  // namespace fen
