// adaptive_grid.cpp — learning the cell probabilities (adaptive_grid.h).
#include "emission/adaptive_grid.h"

#include <algorithm>
#include <cmath>

#include "io/state_io.h"
#include "util/error.h"
#include "util/fnv.h"

namespace fen {

namespace {

// Parts of a cell: 4 * direction quarter + origin quarter.
constexpr int kOriginQuarter[4][4] = {{0, 4, 8, 12}, {1, 5, 9, 13}, {2, 6, 10, 14}, {3, 7, 11, 15}};
constexpr int kSkyQuarter[4][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {8, 9, 10, 11}, {12, 13, 14, 15}};
constexpr int kAll[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};

}  // namespace

double GridCell::boxArea() const { return std::ldexp(1.0, -2 * static_cast<int>(depth)); }
double GridCell::skyArea() const { return std::ldexp(1.0, -2 * static_cast<int>(skyDepth)); }

void GridCell::Stats::add(const Stats& o)
{
    sum += o.sum;
    sumSq += o.sumSq;
    paths += o.paths;
    connections += o.connections;
}

void GridCell::Stats::scale(double f)
{
    sum *= f;
    sumSq *= f;
    paths *= f;
    connections *= f;
}

GridCell::Stats GridCell::total() const
{
    Stats t;
    for (const Stats& q : part)
        t.add(q);
    return t;
}

AdaptiveGrid::AdaptiveGrid(std::vector<GridCell> cells, const GridLearning& learning, SkySplit skySplit)
    : cells_(std::move(cells)), learning_(learning), skySplit_(std::move(skySplit))
{
    double sum = 0.0;
    for (const GridCell& c : cells_)
        sum += c.base;
    if (cells_.empty() || !(sum > 0.0))
        throw Error("adaptive emission: no cell of the grid carries light");
    for (GridCell& c : cells_) {
        c.base /= sum;
        c.prob = c.base;
    }
    learned_.assign(cells_.size(), 0.0);
    for (std::size_t i = 0; i < cells_.size(); ++i)
        learned_[i] = cells_[i].base;
}

void AdaptiveGrid::addPass(const std::vector<GridCell::Stats>& parts)
{
    for (std::size_t i = 0; i < cells_.size(); ++i)
        for (int q = 0; q < 16; ++q) {
            const GridCell::Stats& s = parts[16 * i + q];
            cells_[i].part[q].add(s);
            totalPaths_ += s.paths;
            totalConnections_ += s.connections;
        }
}

// The prior's pseudo-path: base-weighted means over the visited cells, per path.
void AdaptiveGrid::computePrior()
{
    double first = 0.0, second = 0.0, rate = 0.0, weight = 0.0, pooled = 0.0;
    for (const GridCell& c : cells_) {
        const GridCell::Stats t = c.total();
        if (t.paths > 0.0) {
            first += c.base * t.sum / t.paths;
            second += c.base * t.sumSq / t.paths;
            if (t.connections > 0.0)
                pooled += c.base * t.sum * t.sum / (t.paths * t.connections);
            rate += c.base * t.connections / t.paths;
            weight += c.base;
        }
    }
    priorFirst_ = weight > 0.0 ? first / weight : 0.0;
    priorSecond_ = weight > 0.0 ? second / weight : 0.0;
    priorRate_ = weight > 0.0 ? rate / weight : 0.0;
    // g: the visited cells' squares over their pooled figures (a cell without connections has
    // neither, so `second` is the squares' sum).
    spread_ = pooled > 0.0 && second > 0.0 ? second / pooled : 1.0;
    seen_ = learning_.estimate != GridEstimate::Squares ? priorFirst_ > 0.0 && priorRate_ > 0.0
                                                       : priorSecond_ > 0.0;
}

double AdaptiveGrid::secondMoment(const GridCell::Stats& s, double k) const
{
    const double first = s.sum + k * priorFirst_;
    const double pooled = first * first / ((s.paths + k) * (s.connections + k * priorRate_));
    const double squares = (s.sumSq + k * priorSecond_) / (s.paths + k);
    switch (learning_.estimate) {
    case GridEstimate::Pooled: return pooled;
    case GridEstimate::Squares: return squares;
    case GridEstimate::Larger: return std::max(spread_ * pooled, squares);
    }
    return pooled;
}

double AdaptiveGrid::value(const GridCell& c, const int* parts, int n, double baseShare) const
{
    double m = 0.0;
    for (int i = 0; i < n; ++i)
        m += secondMoment(c.part[parts[i]], learning_.priorPaths / 16.0) / n;
    return baseShare * c.base * std::sqrt(m);
}

double AdaptiveGrid::estimate(const GridCell& c) const
{
    if (!seen_)
        return c.base;  // nothing seen anywhere yet: the base density is all there is to go by
    return value(c, kAll, 16, 1.0);
}

void AdaptiveGrid::computeLearned()
{
    computePrior();
    learned_.assign(cells_.size(), 0.0);
    double total = 0.0;
    for (std::size_t i = 0; i < cells_.size(); ++i) {
        learned_[i] = estimate(cells_[i]);
        total += learned_[i];
    }
    // Statistics out of range (an overflowed sum) must not take the grid with them: the base
    // density is what is known for sure, and the defensive share needs finite numbers to hold.
    if (!(total > 0.0) || !std::isfinite(total)) {
        total = 0.0;
        for (std::size_t i = 0; i < cells_.size(); ++i)
            total += learned_[i] = cells_[i].base;
    }
    for (double& v : learned_)
        v /= total;
}

std::size_t AdaptiveGrid::update()
{
    computePrior();
    std::vector<double> val(cells_.size());
    double objective = 0.0;
    for (std::size_t i = 0; i < cells_.size(); ++i) {
        val[i] = estimate(cells_[i]);
        objective += val[i];
    }
    std::vector<GridCell> next;
    next.reserve(cells_.size());
    std::size_t splits = 0;
    std::size_t count = cells_.size();
    for (std::size_t i = 0; i < cells_.size(); ++i) {
        const GridCell& c = cells_[i];
        // The objective after splitting along the origin box, or along the direction box: the
        // children's values (a quarter of the base each way: see adaptive_grid.h, the base shares
        // cancel in a child's value).
        double gainOrigin = -1.0, gainSky = -1.0;
        if (seen_ && count + 3 <= learning_.maxCells &&
            c.total().connections >= learning_.minConnectionsToSplit) {
            if (c.depth < learning_.maxDepth) {
                double children = 0.0;
                for (const auto& q : kOriginQuarter)
                    children += value(c, q, 4, 0.25);
                gainOrigin = val[i] - children;
            }
            if (!c.sun && c.skyDepth < learning_.maxSkyDepth) {
                double children = 0.0;
                for (const auto& q : kSkyQuarter)
                    children += value(c, q, 4, 0.25);
                gainSky = val[i] - children;
            }
        }
        const double gain = std::max(gainOrigin, gainSky);
        if (!(gain >= learning_.splitGain * objective)) {
            next.push_back(c);
            continue;
        }
        ++splits;
        count += 3;
        if (gainOrigin >= gainSky) {
            for (std::uint32_t q = 0; q < 4; ++q) {
                GridCell k = c;
                k.depth = c.depth + 1;
                k.ix = 2 * c.ix + (q & 1u);
                k.iy = 2 * c.iy + (q >> 1);
                k.base = c.base / 4.0;
                // The child is the parent's origin quarter q: its parts' statistics, spread evenly
                // over the child's own origin quarters (not known yet).
                for (int v = 0; v < 4; ++v) {
                    GridCell::Stats s = c.part[4 * v + q];
                    s.scale(0.25);
                    for (int x = 0; x < 4; ++x)
                        k.part[4 * v + x] = s;
                }
                next.push_back(k);
            }
        } else {
            double share[4];
            skySplit_(c, share);
            for (std::uint32_t q = 0; q < 4; ++q) {
                GridCell k = c;
                k.skyDepth = c.skyDepth + 1;
                k.is = 2 * c.is + (q & 1u);
                k.it = 2 * c.it + (q >> 1);
                k.base = c.base * share[q];
                // Lambda is relative to the base density, uniform in solid angle inside a cell: in
                // the child it is share * 4 times the parent's there, so its sums shrink by that.
                const double f = 1.0 / (4.0 * std::max(share[q], 1e-300));
                for (int x = 0; x < 4; ++x) {
                    GridCell::Stats s = c.part[4 * q + x];
                    s.sum *= f;
                    s.sumSq *= f * f;
                    s.scale(0.25);
                    for (int v = 0; v < 4; ++v)
                        k.part[4 * v + x] = s;
                }
                next.push_back(k);
            }
        }
    }
    cells_ = std::move(next);
    computeLearned();
    const double alpha = learning_.defensive;
    for (std::size_t i = 0; i < cells_.size(); ++i)
        cells_[i].prob = (1.0 - alpha) * learned_[i] + alpha * cells_[i].base;
    return splits;
}

double AdaptiveGrid::predictedVariance(const std::vector<double>& prob)
{
    computePrior();
    double v = 0.0;
    for (std::size_t i = 0; i < cells_.size(); ++i) {
        const double e = estimate(cells_[i]);
        if (e > 0.0)
            v += e * e / prob.at(i);
    }
    return v;
}

void AdaptiveGrid::setProbabilities(const std::vector<double>& p)
{
    if (p.size() != cells_.size())
        throw Error(cat("adaptive emission: ", p.size(), " probabilities for ", cells_.size(), " cells"));
    double sum = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (!(p[i] >= 0.0) || (cells_[i].base > 0.0 && !(p[i] > 0.0)))
            throw Error(cat("adaptive emission: cell ", i, " has probability ", p[i]));
        sum += p[i];
    }
    for (std::size_t i = 0; i < p.size(); ++i)
        cells_[i].prob = p[i] / sum;
}

std::uint64_t AdaptiveGrid::checksum() const
{
    Fnv f;  // over the cells' fields
    for (const GridCell& c : cells_) {
        const std::uint32_t id[8] = {c.sun ? 1u : 0u, c.region, c.depth, c.ix, c.iy, c.skyDepth, c.is, c.it};
        f.value(id);
        f.value(c.prob);
    }
    return f.h;
}

void AdaptiveGrid::save(StateWriter& w) const
{
    std::vector<std::uint64_t> ids;
    std::vector<double> reals;
    for (const GridCell& c : cells_) {
        for (std::uint32_t v : {c.sun ? 1u : 0u, c.region, c.depth, c.ix, c.iy, c.skyDepth, c.is, c.it})
            ids.push_back(v);
        reals.push_back(c.base);
        reals.push_back(c.prob);
        for (const GridCell::Stats& s : c.part)
            for (double v : {s.sum, s.sumSq, s.paths, s.connections})
                reals.push_back(v);
    }
    w.u64("grid.cells", cells_.size());
    w.u64s("grid.cell_ids", ids);
    w.f64s("grid.cell_values", reals);
    w.f64s("grid.learned", learned_);
    w.f64s("grid.prior", {priorFirst_, priorRate_, priorSecond_, seen_ ? 1.0 : 0.0, totalPaths_, totalConnections_});
}

void AdaptiveGrid::load(StateReader& r, std::uint32_t regions)
{
    constexpr std::size_t kIds = 8, kReals = 2 + 16 * 4;
    const std::size_t n = r.u64("grid.cells", learning_.maxCells);
    if (n == 0)
        r.fail("grid.cells", "an empty grid");
    const std::vector<std::uint64_t> ids = r.u64s("grid.cell_ids", n * kIds);
    const std::vector<double> reals = r.f64s("grid.cell_values", n * kReals, true);
    if (ids.size() != n * kIds)
        r.fail("grid.cell_ids", cat(ids.size(), " values where ", n * kIds, " belong"));
    std::vector<double> learned = r.f64s("grid.learned", n, true);
    const std::vector<double> prior = r.f64s("grid.prior", 6, true);
    std::vector<GridCell> cells(n);
    for (std::size_t i = 0; i < n; ++i) {
        GridCell& c = cells[i];
        const std::uint64_t* id = ids.data() + kIds * i;
        const bool fits = id[0] <= 1 && id[1] < regions && id[2] <= learning_.maxDepth &&
                          id[3] >> id[2] == 0 && id[4] >> id[2] == 0 && id[5] <= learning_.maxSkyDepth &&
                          id[6] >> id[5] < learning_.skyRoots && id[7] >> id[5] == 0;
        if (!fits)
            r.fail("grid.cell_ids", cat("cell ", i, " lies outside the grid's limits"));
        c.sun = id[0] == 1;
        c.region = static_cast<std::uint32_t>(id[1]);
        c.depth = static_cast<std::uint32_t>(id[2]);
        c.ix = static_cast<std::uint32_t>(id[3]);
        c.iy = static_cast<std::uint32_t>(id[4]);
        c.skyDepth = static_cast<std::uint32_t>(id[5]);
        c.is = static_cast<std::uint32_t>(id[6]);
        c.it = static_cast<std::uint32_t>(id[7]);
        const double* v = reals.data() + kReals * i;
        c.base = v[0];
        c.prob = v[1];
        for (int q = 0; q < 16; ++q)
            c.part[q] = {v[2 + 4 * q], v[3 + 4 * q], v[4 + 4 * q], v[5 + 4 * q]};
        if (!(c.base >= 0.0 && c.prob >= 0.0 && c.prob <= 1.0) || (c.base > 0.0 && !(c.prob > 0.0)))
            r.fail("grid.cell_values", cat("cell ", i, " has no valid probability"));
    }
    cells_ = std::move(cells);
    learned_ = std::move(learned);
    priorFirst_ = prior[0];
    priorRate_ = prior[1];
    priorSecond_ = prior[2];
    seen_ = prior[3] != 0.0;
    totalPaths_ = prior[4];
    totalConnections_ = prior[5];
}

std::uint32_t AdaptiveGrid::deepest() const
{
    std::uint32_t d = 0;
    for (const GridCell& c : cells_)
        d = std::max(d, c.depth);
    return d;
}

std::uint32_t AdaptiveGrid::deepestSky() const
{
    std::uint32_t d = 0;
    for (const GridCell& c : cells_)
        d = std::max(d, c.skyDepth);
    return d;
}

}  // namespace fen
