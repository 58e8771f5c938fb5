// source_table.h — what the emission strategies draw light sources from (DESIGN.md §3.1): the
// sky's arrays (host and device), the integer tables that choose a source, and the `uniform`
// strategy's emission box, source choice and path weights (kernels/lib/emit_source.h,
// lib/emit_uniform.h, lib/sky.h and lib/sampling.h are the device half).
//
// One integer table chooses both the source and the sky cell from a path's first 32 random bits:
// entry 0 is the sun, entry 1 + k is sky cell k, each with probability n_e / 2^32 exactly, so the
// weights use the probabilities the device realises. For `uniform`, each source gets units in
// proportion to its flux into the emission box (so sky paths carry nearly equal weights), and
// every source that sends light gets at least one unit.
#pragma once

#include <optional>
#include <vector>

#include "cl/context.h"
#include "scene/scene.h"
#include "shared/fen_emission.h"
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

// The node angles and luminances of a SkyTables on the device (lib/sky.h), shared by the camera
// pass and the strategies that sample the scene's sky.
struct DeviceSky {
    DeviceSky(ocl::Context& ctx, const SkyTables& t);
    cl::Buffer theta, phi, values;
};

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

// The box every `uniform` line enters (DESIGN.md §3.1): the scene's bounds, a little enlarged so
// that geometry on their faces is inside. Seen along a unit direction v it covers
// A(v) = sum_a |v_a| (the area of the faces normal to a): a line through the box's silhouette is
// the only kind that can meet a triangle.
struct EmissionBox {
    glm::dvec3 min{0.0}, size{0.0};
    // The area of a face normal to each axis.
    glm::dvec3 faceAreas() const { return {size.y * size.z, size.z * size.x, size.x * size.y}; }
    double silhouetteArea(const glm::dvec3& v) const { return glm::dot(glm::abs(v), faceAreas()); }
};
EmissionBox emissionBox(const Scene& scene);

// The `uniform` strategy's sources: the emission box, the table choosing the sun or a sky cell in
// proportion to its flux through the box's silhouette, and weights (the kernel multiplies in the
// silhouette's area A(v) per path).
struct UniformSources {
    EmissionBox box;
    double sunFlux = 0.0;          // luminous flux into the box (lm; A at the sun's axis)
    double skyFlux = 0.0;          // exact for the goniogram: sum over cells of ∫ A(w) g dw
    double pSun = 0.0;             // realised probability that a path starts at the sun
    IntegerCdf sources;            // entry 0: the sun; entry 1 + k: sky cell k
    std::vector<float> skyFactor;  // per sky cell: B_k / P(entry 1 + k), see lib/sky.h
    glm::dvec3 sunWeight{0.0};     // rgb weight of a sun path over A(v): E / P(sun)
};

// `sky` and `g` describe the same sky (makeSkyTables(g)); the cells' flux into the box needs the
// goniogram itself.
UniformSources setupUniformEmission(const Scene& scene, const SkyTables& sky, const std::optional<Goniogram>& g);

// The sphere every emitted path starts outside of: the scene's bounding sphere, a little larger
// (rays must start outside it; adaptive's disk must cover every triangle's projection).
void emissionSphere(const Scene& scene, glm::dvec3* centre, double* radius_m);

// The brightest plausible diffuse luminance of the scene (cd/m^2): what fixed-point scales are
// set against (max of E_sun / pi and the sky's brightest node).
double referenceLuminance(const Scene& scene, const SkyTables& sky);

// The normal illuminance of the sun as luminance-weighted lux (Y of its RGB; 0 without a sun).
double sunIlluminanceY_lux(const Scene& scene);

// A disk sun's directions are uniform in its cone, so a plane facing it receives E (1 + cos a) / 2
// per unit weight: this restores its normal illuminance E.
double sunConeFactor(const Sun& sun);

// The device parameters of a source table (kernels/shared/fen_emission.h SourceParams); `box`: the
// uniform strategy's, none for a table that starts no uniform line.
dev::SourceParams sourceParams(const IntegerCdf& sources, const glm::dvec3& sunWeight,
                               const EmissionBox* box = nullptr);

}  // namespace fen
