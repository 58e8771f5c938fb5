// emission_setup.cpp — uniform emission parameters and sky tables (emission_setup.h).
#include "render/emission_setup.h"

#include <algorithm>
#include <cmath>

namespace fen {

SkyTables makeSkyTables(const std::optional<Goniogram>& sky)
{
    SkyTables t;
    if (!sky || sky->integral() <= 0.0) {
        t.theta = t.phi = t.values = t.factor = {0.0f};
        t.cdf = {0};
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
    // Cells by their integral of g sin(theta): the sampled direction's density then tracks g per
    // steradian, so sky paths carry nearly equal weights. Integer units of 2^-32: every cell with
    // light gets at least one (none is lost), the units sum to exactly 2^32, and the weight uses
    // the probability the device realises.
    std::vector<double> w(t.cells);
    double total = 0.0;
    for (std::uint32_t i = 0; i + 1 < t.thetaNodes; ++i)
        for (std::uint32_t j = 0; j + 1 < t.phiNodes; ++j) {
            const double I = g.cellIntegralSin(i, j);
            w[i * (t.phiNodes - 1) + j] = I;
            total += I;
        }
    t.integral_cd_m2_sr = total;
    const double units = 4294967296.0;
    std::vector<std::uint64_t> n(t.cells);
    std::uint64_t sum = 0;
    std::uint32_t largest = 0;
    for (std::uint32_t k = 0; k < t.cells; ++k) {
        n[k] = w[k] > 0.0 ? std::max<std::uint64_t>(1, static_cast<std::uint64_t>(w[k] / total * units))
                          : 0;
        sum += n[k];
        if (n[k] > n[largest])
            largest = k;
    }
    n[largest] += (std::uint64_t{1} << 32) - sum;  // rounding remainder: a few units at most
    t.cdf.resize(t.cells + 1);
    t.cdf[0] = 0;
    for (std::uint32_t k = 0; k < t.cells; ++k)
        t.cdf[k + 1] = t.cdf[k] + n[k];
    t.factor.resize(t.cells);
    for (std::uint32_t k = 0; k < t.cells; ++k) {
        const std::uint32_t i = k / (t.phiNodes - 1), j = k % (t.phiNodes - 1);
        t.factor[k] = n[k] > 0 ? static_cast<float>(g.cellIntegralFlat(i, j) * units /
                                                    static_cast<double>(n[k]))
                               : 0.0f;
    }
    return t;
}

EmissionSetup setupUniformEmission(const Scene& scene, const SkyTables& sky)
{
    EmissionSetup e;
    const Aabb& b = scene.bounds;
    if (!b.empty()) {
        e.sphereCentre = glm::dvec3(b.center());
        e.sphereRadius_m = 0.5 * glm::length(glm::dvec3(b.extent()));
    }
    // A little margin: rays must start outside the sphere and cover every triangle's projection.
    e.sphereRadius_m = e.sphereRadius_m * 1.001 + 1e-3;
    const double disk = M_PI * e.sphereRadius_m * e.sphereRadius_m;
    const glm::dvec3 E = scene.sun.present ? scene.sun.illuminanceRgb_lux : glm::dvec3(0.0);
    const double sunY = 0.2126 * E.r + 0.7152 * E.g + 0.0722 * E.b;
    e.sunFlux = sunY * disk;
    e.skyFlux = sky.integral_cd_m2_sr * disk;
    const double total = e.sunFlux + e.skyFlux;
    if (total > 0.0) {
        // An integer threshold on 32 random bits: P(sun) is exactly threshold / 2^32, and both
        // sources stay possible whenever both send light.
        if (e.skyFlux <= 0.0) {
            e.sunThreshold = 0xFFFFFFFFu;
            e.pSun = 1.0;
        } else if (e.sunFlux > 0.0) {
            const double t = std::round(e.sunFlux / total * 4294967296.0);
            e.sunThreshold = static_cast<std::uint32_t>(std::clamp(t, 1.0, 4294967294.0));
            e.pSun = e.sunThreshold / 4294967296.0;
        }
        if (e.pSun > 0.0)
            e.sunWeight = E * disk / e.pSun;
        if (e.pSun < 1.0)
            e.skyWeight = disk / (1.0 - e.pSun);
    }
    e.referenceLuminance_cd_m2 =
        std::max({sunY / M_PI, sky.maxLuminance_cd_m2, 1e-6});
    return e;
}

void fillEmissionParams(const EmissionSetup& e, const SkyTables& sky, dev::RenderParams& p)
{
    p.sphere = {static_cast<float>(e.sphereCentre.x), static_cast<float>(e.sphereCentre.y),
                static_cast<float>(e.sphereCentre.z), static_cast<float>(e.sphereRadius_m)};
    p.sun_weight = {static_cast<float>(e.sunWeight.r), static_cast<float>(e.sunWeight.g),
                    static_cast<float>(e.sunWeight.b), 0.0f};
    p.sky_weight = {static_cast<float>(e.skyWeight), 0.0f, 0.0f, 0.0f};
    p.sun_threshold = e.sunThreshold;
    p.sky_cells = sky.cells;
    p.sky_theta_nodes = sky.thetaNodes;
    p.sky_phi_nodes = sky.phiNodes;
}

}  // namespace fen
