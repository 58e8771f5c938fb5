// uniform_emission.cpp — the emission box, the uniform source table and the source tables' device
// parameters (uniform_emission.h).
#include "emission/uniform_emission.h"

#include "emission/light_levels.h"

namespace fen {

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
