// portal_emission.cpp — eqs. (1)-(2) tables for portal emission (portal_emission.h).
#include "emission/portal_emission.h"

#include <chrono>
#include <cmath>

#include "sky/goniogram.h"
#include "util/error.h"

namespace fen {

PortalOverlap parsePortalOverlap(const std::string& s)
{
    if (s == "reject")
        return PortalOverlap::Reject;
    if (s == "weight")
        return PortalOverlap::Weight;
    if (s == "none")
        return PortalOverlap::None;
    throw Error(cat("--portal-overlap '", s, "': expected reject, weight or none"));
}

namespace {

// sum_g A_g ∫_cell |v.n_g| g dv for cell (i, j).
double cellPortalWeight(const Goniogram& g, const PortalSet& portals, std::size_t i, std::size_t j)
{
    const double t0 = g.theta()[i], t1 = g.theta()[i + 1], p0 = g.phi()[j], p1 = g.phi()[j + 1];
    const glm::dvec3 F = g.cellDirectionIntegral(i, j);
    double total = 0.0;
    for (const PortalGroup& grp : portals.groups) {
        // Does the plane cut the cell? Signs of v.n over a 5 x 5 lattice of the cell.
        bool pos = false, neg = false;
        for (int a = 0; a <= 4; ++a)
            for (int b = 0; b <= 4; ++b) {
                const double d = glm::dot(skyDirection(t0 + (t1 - t0) * a / 4.0, p0 + (p1 - p0) * b / 4.0),
                                          grp.normal);
                pos = pos || d > 0.0;
                neg = neg || d < 0.0;
            }
        if (!(pos && neg)) {
            total += grp.area_m2 * std::fabs(glm::dot(F, grp.normal));
            continue;
        }
        double s = 0.0;
        const int m = 8;
        for (int a = 0; a < m; ++a)
            for (int b = 0; b < m; ++b) {
                const double th = t0 + (t1 - t0) * (a + 0.5) / m, ph = p0 + (p1 - p0) * (b + 0.5) / m;
                s += std::fabs(glm::dot(skyDirection(th, ph), grp.normal)) * g.eval(th, ph) * std::sin(th);
            }
        total += grp.area_m2 * s * (t1 - t0) * (p1 - p0) / (m * m);
    }
    return total;
}

}  // namespace

PortalEmission setupPortalEmission(const Scene& scene, const SkyTables& sky,
                                   const std::optional<Goniogram>& goniogram,
                                   const std::string& portalOverride, int bvhWidth)
{
    const auto start = std::chrono::steady_clock::now();
    PortalEmission e;
    e.portals = collectPortals(scene, portalOverride);

    const glm::dvec3 E = scene.sun.present ? scene.sun.illuminanceRgb_lux : glm::dvec3(0.0);
    const double sunY = 0.2126 * E.r + 0.7152 * E.g + 0.0722 * E.b;
    e.sunFlux_lm = sunY * e.portals.projectedArea(scene.sun.travelDirection);
    std::vector<double> w{e.sunFlux_lm};
    if (goniogram && sky.cells > 0) {
        std::vector<double> cells(sky.cells);
        double mean = 0.0;
        for (std::uint32_t i = 0; i + 1 < sky.thetaNodes; ++i)
            for (std::uint32_t j = 0; j + 1 < sky.phiNodes; ++j) {
                const std::uint32_t k = i * (sky.phiNodes - 1) + j;
                cells[k] = cellPortalWeight(*goniogram, e.portals, i, j);
                e.skyFlux_lm += cells[k];
                mean += cells[k] / sky.cells;
            }
        // A cell with sky in it keeps a sliver of probability even if the estimate above were 0:
        // a cell never sampled loses its light (bias); one sampled rarely only costs variance.
        for (std::uint32_t k = 0; k < sky.cells; ++k)
            w.push_back(sky.cellSin[k] > 0.0 ? std::max(cells[k], 1e-9 * mean) : 0.0);
    }
    if (e.sunFlux_lm + e.skyFlux_lm <= 0.0)
        w[0] = 1.0;  // no light reaches the portals: the (zero-weight) sun, so the table is valid
    e.sources = makeIntegerCdf(w);
    e.pSun = e.sunFlux_lm > 0.0 ? e.sources.probability(0) : 0.0;
    if (e.pSun > 0.0)
        e.sunWeight = E / e.pSun;
    e.skyFactor.assign(std::max<std::uint32_t>(1, sky.cells), 0.0f);
    for (std::uint32_t k = 0; k < sky.cells; ++k) {
        const double p = e.sources.probability(1 + k);
        e.skyFactor[k] = p > 0.0 ? static_cast<float>(sky.cellFlat[k] / p) : 0.0f;
    }

    for (const PortalGroup& g : e.portals.groups) {
        e.groups.push_back({static_cast<float>(g.normal.x), static_cast<float>(g.normal.y),
                            static_cast<float>(g.normal.z), static_cast<float>(g.area_m2)});
        e.groupRange.push_back(g.first);
        e.groupRange.push_back(g.count);
        const IntegerCdf c = makeIntegerCdf(std::vector<double>(
            e.portals.area_m2.begin() + g.first, e.portals.area_m2.begin() + g.first + g.count));
        e.triangleCdf.insert(e.triangleCdf.end(), c.cdf.begin(), c.cdf.end());
    }
    for (const Triangle& t : e.portals.triangles)
        for (const glm::vec3* p : {&t.p0, &t.p1, &t.p2})
            e.vertices.push_back({p->x, p->y, p->z, 0.0f});
    e.bvh = flattenBvh(buildBinnedSah(e.portals.triangles), e.portals.triangles, bvhWidth);
    e.precomputeSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return e;
}

}  // namespace fen
