// portal_emission.h — the tables of the `portal` strategy (DESIGN.md §3.2, the paper's method 1):
// rays are emitted only through the user-marked portals. (The strategy itself, its buffers and
// report: portal_strategy.h.)
//
// Per path (kernels/lib/emit_portal.h): one entry of a joint table picks the sun or a sky cell;
// the direction v is the sun's, or sampled in the cell with density proportional to g (as in
// `uniform`); a portal group is chosen from the table of v's direction bin (the sun, or a block of
// sky cells) with probability P(g | bin) proportional to A_g ∫_bin |v.n_g| g dv -- eq. (1)
// averaged over the bin, so the choice is one read however many portal planes there are, where
// eq. (1) per direction loops over all of them (measured: docs/results/portal_tables.md) -- then a
// triangle by area, then x uniformly on it. Per unit of area orthogonal to v, the crossing of
// group g was generated with density d_g = P(entry) q(v) P(g | bin) / (A_g |v.n_g|); a ray crossing
// N(x, v) portal triangles is generated N ways, and keeping it with probability 1/N (the paper's
// fix) or dividing its weight by N (--portal-overlap weight), with the weight of the crossing
// drawn, is unbiased whatever the d_g: sum over crossings of d_c (1/N) / d_c = 1. Weights: sun
// E s / P(sun); sky s factor_k sin(theta), factor_k = B_k / P(entry k) (see lib/sky.h), with
// s = A_g |v.n_g| / P(g | bin) (= W(v) = sum_g A_g |v.n_g| when the choice follows eq. (1)
// exactly, as it does with one portal plane).
// The table follows eqs. (1)-(2): the sun by E W(v_sun), cell k by sum_g A_g ∫_k |v.n_g| g dv,
// which is A_g |F_k . n_g| (F_k = ∫_k v g dv) where the cell lies on one side of the plane, and a
// converged integral where the plane cuts it. These set probabilities only; the weights use the
// probabilities realised, so any error there would cost variance, never bias.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "bvh_flat.h"
#include "emission/portals.h"
#include "shared/fen_emission.h"
#include "sky/sky_tables.h"
#include "util/integer_cdf.h"

namespace fen {

enum class PortalOverlap : std::uint32_t {
    Reject = FEN_OVERLAP_REJECT,
    Weight = FEN_OVERLAP_WEIGHT,
    None = FEN_OVERLAP_NONE
};
PortalOverlap parsePortalOverlap(const std::string& s);  // reject | weight | none

struct PortalEmission {
    PortalSet portals;
    IntegerCdf sources;             // entry 0: the sun; entry 1 + k: sky cell k
    std::vector<float> skyFactor;   // per cell: B_k / P(entry 1 + k)
    glm::dvec3 sunWeight{0.0};      // E_rgb / P(sun): the device multiplies by A_g |v.n_g| / P(g | bin)
    double sunFlux_lm = 0.0;        // flux through the portals' projections (overlaps counted N times)
    double skyFlux_lm = 0.0;
    double pSun = 0.0;
    double precomputeSeconds = 0.0;
    // Device arrays (kernels/lib/emit_portal.h).
    std::vector<dev::fen_float4> groups;  // xyz: unit normal; w: area (m^2)
    // Group tables by direction bin: bin 0 the sun, 1 + b a block of sky cells. Per bin an alias
    // table of 2^(32 - groupAliasShift) columns (lib/sampling.h alias_pick) and, per group,
    // A_g / P(g | bin) as realised.
    std::vector<std::uint32_t> groupAlias;
    std::vector<float> groupRatio;
    std::uint32_t groupAliasShift = 31;
    std::vector<std::uint32_t> cellBin;   // per sky cell: its bin
    std::vector<std::uint32_t> groupRange;  // per group: first triangle, count
    std::vector<std::uint64_t> triangleCdf;  // group g: entries [first + g, first + g + count], 0..2^32
    std::vector<dev::fen_float4> vertices;  // 3 per portal triangle
    FlatBvh bvh;                            // the portal triangles alone, for N(x, v)
};

PortalEmission setupPortalEmission(const Scene& scene, const SkyTables& sky,
                                   const std::optional<Goniogram>& goniogram,
                                   const std::string& portalOverride, int bvhWidth);

}  // namespace fen
