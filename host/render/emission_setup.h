// emission_setup.h — the host half of the `uniform` strategy (DESIGN.md §3.1): the emission disk,
// the choice of source (the sun, or one cell of the sky), path weights, and the sky's arrays
// (kernels/lib/emit_uniform.h, lib/sky.h and lib/sampling.h are the device half).
//
// One integer table chooses both the source and the sky cell from a path's first 32 random bits:
// entry 0 is the sun, entry 1 + k is sky cell k, each with probability n_e / 2^32 exactly, so the
// weights use the probabilities the device realises. Cells get units in proportion to their
// integral of g sin(theta) (so sky paths carry nearly equal weights), the sun in proportion to
// its flux through the disk, and every source that sends light gets at least one unit.
#pragma once

#include <optional>
#include <vector>

#include "scene/scene.h"
#include "shared/fen_render.h"
#include "sky/goniogram.h"

namespace fen {

// A goniogram as the device reads it. With no sky: nodes counts 0, arrays hold one zero each
// (OpenCL buffers cannot be empty).
struct SkyTables {
    std::vector<float> theta, phi, values;  // node angles (rad) and luminances (cd/m^2)
    std::vector<double> cellSin, cellFlat;  // per cell: ∫∫ g sin(theta), ∫∫ g (d theta d phi)
    std::uint32_t thetaNodes = 0, phiNodes = 0, cells = 0;
    double integral_cd_m2_sr = 0.0;         // ∫ g dω over the upper hemisphere
    double maxLuminance_cd_m2 = 0.0;
};
SkyTables makeSkyTables(const std::optional<Goniogram>& sky);

// An integer CDF over n entries (cdf[0] = 0 .. cdf[n] = 2^32): entry e has probability
// (cdf[e+1] - cdf[e]) / 2^32 exactly. The device draws from it with one read: an alias table of
// 2^(32 - aliasShift) >= n columns of 2^aliasShift values each (lib/sampling.h alias_pick;
// column j gives entry j to its first alias[2j] values and entry alias[2j+1] to the rest). The
// columns are filled with integers, so every entry keeps exactly its cdf units.
struct IntegerCdf {
    std::vector<std::uint64_t> cdf;
    std::vector<std::uint32_t> alias;  // per column: threshold, alias entry
    std::uint32_t aliasShift = 31;
    double probability(std::size_t e) const
    {
        return static_cast<double>(cdf[e + 1] - cdf[e]) / 4294967296.0;
    }
    // The entry the device draws for 32 random bits r (alias_pick); needs the alias table.
    std::uint32_t pick(std::uint32_t r) const;
};
// Units in proportion to `weight` (>= 0), at least one for every positive weight; `alias`: also
// the alias table, not needed for binary searches.
IntegerCdf makeIntegerCdf(const std::vector<double>& weight, bool alias = true);

struct EmissionSetup {
    glm::dvec3 sphereCentre{0.0};
    double sphereRadius_m = 0.0;
    double sunFlux = 0.0;          // luminous flux through the emission disk (lm)
    double skyFlux = 0.0;
    double pSun = 0.0;             // realised probability that a path starts at the sun
    IntegerCdf sources;            // entry 0: the sun; entry 1 + k: sky cell k
    std::vector<float> skyFactor;  // per sky cell: B_k / P(entry 1 + k), see lib/sky.h
    glm::dvec3 sunWeight{0.0};     // rgb weight of a sun path: E pi R^2 / P(sun)
    double skyWeight = 0.0;        // pi R^2: times factor_k sin(theta) for a sky path
    double referenceLuminance_cd_m2 = 1.0;  // brightest plausible diffuse luminance (fixed-point scale)
};

EmissionSetup setupUniformEmission(const Scene& scene, const SkyTables& sky);

// Writes the emission fields of `p` (sphere, sun, sky sizes, source alias shift).
void fillEmissionParams(const EmissionSetup& e, const SkyTables& sky, dev::RenderParams& p);

}  // namespace fen
