// source_table.cpp — sky arrays, integer source tables and the uniform strategy's sources
// (source_table.h).
#include "emission/source_table.h"

#include <algorithm>
#include <cmath>

namespace fen {

namespace {

constexpr double kUnits = 4294967296.0;  // 2^32

}  // namespace

IntegerCdf makeIntegerCdf(const std::vector<double>& weight, bool alias)
{
    IntegerCdf c;
    double total = 0.0;
    for (double w : weight)
        total += std::max(0.0, w);
    std::vector<std::uint64_t> n(weight.size(), 0);
    std::uint64_t sum = 0;
    std::size_t largest = 0;
    for (std::size_t e = 0; e < weight.size(); ++e) {
        if (weight[e] > 0.0)
            n[e] = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(weight[e] / total * kUnits));
        sum += n[e];
        if (n[e] > n[largest])
            largest = e;
    }
    // The rounding remainder (a few units, either sign) goes to the largest entry.
    n[largest] = n[largest] + (std::uint64_t{1} << 32) - sum;
    c.cdf.assign(weight.size() + 1, 0);
    for (std::size_t e = 0; e < weight.size(); ++e)
        c.cdf[e + 1] = c.cdf[e] + n[e];
    if (!alias)
        return c;
    // Vose's alias method in integers: 2^bits >= n columns of C = 2^(32 - bits) units each hold
    // 2^32 units in all, as many as the entries. A column short of C takes the rest from an entry
    // with more; what is moved is whole units, so the counts stay exact.
    std::uint32_t bits = 1;
    while ((std::size_t{1} << bits) < weight.size())
        ++bits;
    c.aliasShift = 32 - bits;
    const std::size_t columns = std::size_t{1} << bits;
    const std::uint64_t C = std::uint64_t{1} << c.aliasShift;
    std::vector<std::uint64_t> left(columns, 0);
    std::copy(n.begin(), n.end(), left.begin());
    std::vector<std::uint32_t> small, large;
    for (std::size_t j = columns; j-- > 0;)
        (left[j] < C ? small : large).push_back(static_cast<std::uint32_t>(j));
    c.alias.assign(2 * columns, 0);
    while (!small.empty() && !large.empty()) {
        const std::uint32_t s = small.back(), l = large.back();
        small.pop_back();
        c.alias[2 * s] = static_cast<std::uint32_t>(left[s]);
        c.alias[2 * s + 1] = l;
        left[l] -= C - left[s];
        if (left[l] < C) {
            large.pop_back();
            small.push_back(l);
        }
    }
    // The units left equal C times the columns left, so small is empty and each of these holds
    // exactly C.
    for (std::uint32_t j : large) {
        c.alias[2 * j] = static_cast<std::uint32_t>(C);  // C <= 2^31
        c.alias[2 * j + 1] = j;
    }
    return c;
}

std::uint32_t IntegerCdf::pick(std::uint32_t r) const
{
    const std::uint32_t j = r >> aliasShift;
    const std::uint32_t offset = r & ((std::uint32_t{1} << aliasShift) - 1u);
    return offset < alias[2 * j] ? j : alias[2 * j + 1];
}

SkyTables makeSkyTables(const std::optional<Goniogram>& sky)
{
    SkyTables t;
    if (!sky || sky->integral() <= 0.0) {
        t.theta = t.phi = t.values = {0.0f};
        return t;
    }
    const Goniogram& g = *sky;
    t.thetaNodes = static_cast<std::uint32_t>(g.thetaCount());
    t.phiNodes = static_cast<std::uint32_t>(g.phiCount());
    t.cells = (t.thetaNodes - 1) * (t.phiNodes - 1);
    for (double th : g.theta())
        t.theta.push_back(static_cast<float>(th));
    for (double ph : g.phi())
        t.phi.push_back(static_cast<float>(ph));
    for (double v : g.values()) {
        t.values.push_back(static_cast<float>(v));
        t.maxLuminance_cd_m2 = std::max(t.maxLuminance_cd_m2, v);
    }
    for (std::uint32_t i = 0; i + 1 < t.thetaNodes; ++i)
        for (std::uint32_t j = 0; j + 1 < t.phiNodes; ++j) {
            t.cellSin.push_back(g.cellIntegralSin(i, j));
            t.cellFlat.push_back(g.cellIntegralFlat(i, j));
            t.integral_cd_m2_sr += t.cellSin.back();
        }
    return t;
}

DeviceSky::DeviceSky(ocl::Context& ctx, const SkyTables& t)
    : theta(ctx.buffer(CL_MEM_READ_ONLY, t.theta.size() * 4, "sky nodes", t.theta.data())),
      phi(ctx.buffer(CL_MEM_READ_ONLY, t.phi.size() * 4, "sky nodes", t.phi.data())),
      values(ctx.buffer(CL_MEM_READ_ONLY, t.values.size() * 4, "sky luminances", t.values.data()))
{
}

void emissionSphere(const Scene& scene, glm::dvec3* centre, double* radius_m)
{
    *centre = glm::dvec3(0.0);
    *radius_m = 0.0;
    const Aabb& b = scene.bounds;
    if (!b.empty()) {
        *centre = glm::dvec3(b.center());
        *radius_m = 0.5 * glm::length(glm::dvec3(b.extent()));
    }
    *radius_m = *radius_m * 1.001 + 1e-3;
}

double sunIlluminanceY_lux(const Scene& scene)
{
    const glm::dvec3 E = scene.sun.present ? scene.sun.illuminanceRgb_lux : glm::dvec3(0.0);
    return 0.2126 * E.r + 0.7152 * E.g + 0.0722 * E.b;
}

double sunConeFactor(const Sun& sun) { return 2.0 / (1.0 + std::cos(sun.angularRadiusRad)); }

double referenceLuminance(const Scene& scene, const SkyTables& sky)
{
    return std::max({sunIlluminanceY_lux(scene) / M_PI, sky.maxLuminance_cd_m2, 1e-6});
}

EmissionBox emissionBox(const Scene& scene)
{
    EmissionBox box;
    const Aabb& b = scene.bounds;
    if (b.empty())
        return box;  // nothing to hit: A(v) = 0, every weight zero
    const glm::dvec3 lo(b.lo), hi(b.hi);
    // enlarged like the sphere: a ground plane on the box's face must lie inside it
    const glm::dvec3 margin = 5e-4 * (hi - lo) + glm::dvec3(1e-3 + 1e-6 * glm::length(hi + lo));
    box.min = lo - margin;
    box.size = hi - lo + 2.0 * margin;
    return box;
}

UniformSources setupUniformEmission(const Scene& scene, const SkyTables& sky, const std::optional<Goniogram>& g)
{
    UniformSources e;
    e.box = emissionBox(scene);
    const glm::dvec3 E = scene.sun.present ? scene.sun.illuminanceRgb_lux : glm::dvec3(0.0);
    e.sunFlux = sunIlluminanceY_lux(scene) * e.box.silhouetteArea(scene.sun.travelDirection);

    // Entry 0: the sun, by its flux into the box; entries 1 + k: sky cells (k = i (phi nodes - 1)
    // + j, as in SkyTables), by theirs, ∫_cell A(w) g dw = sum_a (area of the faces normal to a)
    // ∫_cell |w_a| g dw -- two clipped integrals per cell and axis (about 50 ms for a 34k-cell
    // CIE sky, so only the strategies that draw uniform lines pay it, not every SkyTables).
    const glm::dvec3 faceArea = e.box.faceAreas();
    std::vector<double> w{e.sunFlux};
    for (std::uint32_t i = 0; i + 1 < sky.thetaNodes; ++i)
        for (std::uint32_t j = 0; j + 1 < sky.phiNodes; ++j) {
            double flux = 0.0;
            for (int a = 0; a < 3; ++a) {
                glm::dvec3 n(0.0);
                n[a] = 1.0;
                flux += faceArea[a] * (g->cellClippedIntegral(i, j, n) + g->cellClippedIntegral(i, j, -n));
            }
            w.push_back(flux);
            e.skyFlux += flux;
        }
    if (e.sunFlux + e.skyFlux <= 0.0)
        w[0] = 1.0;  // no light (or nothing to hit): a table that draws the (zero-weight) sun
    e.sources = makeIntegerCdf(w);
    e.pSun = e.sunFlux > 0.0 ? e.sources.probability(0) : 0.0;
    if (e.pSun > 0.0)
        e.sunWeight = E * sunConeFactor(scene.sun) / e.pSun;
    e.skyFactor.resize(sky.cells);
    for (std::uint32_t k = 0; k < sky.cells; ++k) {
        const double p = e.sources.probability(1 + k);
        e.skyFactor[k] = p > 0.0 ? static_cast<float>(sky.cellFlat[k] / p) : 0.0f;
    }
    if (e.skyFactor.empty())
        e.skyFactor = {0.0f};
    return e;
}

dev::SourceParams sourceParams(const IntegerCdf& sources, const glm::dvec3& sunWeight, const EmissionBox* box)
{
    dev::SourceParams p{};
    p.sun_weight = {static_cast<float>(sunWeight.r), static_cast<float>(sunWeight.g),
                    static_cast<float>(sunWeight.b), 0.0f};
    if (box) {
        p.box_min = {static_cast<float>(box->min.x), static_cast<float>(box->min.y),
                     static_cast<float>(box->min.z), 0.0f};
        p.box_size = {static_cast<float>(box->size.x), static_cast<float>(box->size.y),
                      static_cast<float>(box->size.z), 0.0f};
    }
    p.alias_shift = sources.aliasShift;
    return p;
}

}  // namespace fen
