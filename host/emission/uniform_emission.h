// uniform_emission.h — the tables of the `uniform` strategy (DESIGN.md §3.1): its emission box,
// the source table choosing the sun or a sky cell, and path weights (kernels/lib/emit_source.h,
// lib/emit_uniform.h are the device half). The source table's device parameters serve the
// `portal` strategy's table too.
//
// One integer table (util/integer_cdf.h) chooses both the source and the sky cell from a path's
// first 32 random bits: entry 0 is the sun, entry 1 + k is sky cell k, each with probability
// n_e / 2^32 exactly, so the weights use the probabilities the device realises. For `uniform`,
// each source gets units in proportion to its flux into the emission box (so sky paths carry
// nearly equal weights), and every source that sends light gets at least one unit.
#pragma once

#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "shared/fen_emission.h"
#include "sky/goniogram.h"
#include "sky/sky_tables.h"
#include "util/integer_cdf.h"

namespace fen {

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

// The device parameters of a source table (kernels/shared/fen_emission.h SourceParams); `box`: the
// uniform strategy's, none for a table that starts no uniform line.
dev::SourceParams sourceParams(const IntegerCdf& sources, const glm::dvec3& sunWeight,
                               const EmissionBox* box = nullptr);

}  // namespace fen
