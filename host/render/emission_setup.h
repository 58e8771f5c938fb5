// emission_setup.h — the host half of the `uniform` strategy (DESIGN.md §3.1): the emission disk,
// the choice between sun and sky, path weights, and the sky's sampling tables
// (kernels/lib/emit_uniform.h and lib/sky.h are the device half).
#pragma once

#include <optional>
#include <vector>

#include "scene/scene.h"
#include "shared/fen_render.h"
#include "sky/goniogram.h"

namespace fen {

// Device arrays of a goniogram (kernels/lib/sky.h). With no sky, all empty but one zero each
// (OpenCL buffers cannot be empty), nodes counts 0.
struct SkyTables {
    std::vector<float> theta, phi, values;  // node angles (rad) and luminances (cd/m^2)
    std::vector<std::uint64_t> cdf;         // cells + 1, 0 .. 2^32: P_k = (cdf[k+1] - cdf[k]) / 2^32
    std::vector<float> factor;              // per cell: B_k / P_k (see lib/sky.h)
    std::uint32_t thetaNodes = 0, phiNodes = 0, cells = 0;
    double integral_cd_m2_sr = 0.0;         // ∫ g dω over the upper hemisphere
    double maxLuminance_cd_m2 = 0.0;
};
SkyTables makeSkyTables(const std::optional<Goniogram>& sky);

struct EmissionSetup {
    glm::dvec3 sphereCentre{0.0};
    double sphereRadius_m = 0.0;
    double sunFlux = 0.0;          // luminous flux through the emission disk (lm)
    double skyFlux = 0.0;
    double pSun = 0.0;             // probability that a path starts at the sun (exact: threshold/2^32)
    std::uint32_t sunThreshold = 0;
    glm::dvec3 sunWeight{0.0};     // rgb weight of a sun path
    double skyWeight = 0.0;        // pi R^2 / P(sky): multiplied by factor_k sin(theta) per path
    double referenceLuminance_cd_m2 = 1.0;  // brightest plausible diffuse luminance (fixed-point scale)
    bool hasLight() const { return sunFlux + skyFlux > 0.0; }
};

EmissionSetup setupUniformEmission(const Scene& scene, const SkyTables& sky);

// Writes the emission fields of `p` (sphere, sun, sky, p_sun, sky table sizes).
void fillEmissionParams(const EmissionSetup& e, const SkyTables& sky, dev::RenderParams& p);

}  // namespace fen
