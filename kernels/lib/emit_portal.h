/* emit_portal.h — the `portal` emission strategy (DESIGN.md §3.2, the paper's method 1; host half
 * and the derivation: host/emission/portal_strategy.h).
 *
 * Per path: the joint table picks the sun or a sky cell (exact probabilities); v is the sun's
 * direction (or in its cone) or sampled in the cell proportionally to g; a portal group is chosen
 * from the group table of v's direction bin (the sun's, or the block of sky cells holding v's
 * cell: eq. 1 averaged over the bin, exact integer shares, one read whatever the number of
 * planes), a triangle of it by area, x uniformly on the triangle; the origin is moved back along
 * -v outside the scene's bounding sphere. N(x, v) = portal triangles on the ray's line (counted in
 * the portals' own BVH from that origin, so every crossing has t > 0; not counted for
 * --portal-overlap none).
 * Weight: sun E s / P(sun), sky s factor_k sin(theta), s = A_g |v.n_g| / P(g | bin) for the
 * group drawn; then divided by N (--portal-overlap weight) or kept with probability 1/N (reject:
 * the path index is spent all the same, so rejected candidates count as emitted paths) -- both
 * unbiased with the drawn crossing's own density (host/emission/portal_emission.h).
 * The complement (PortalParams.complement = c > 0, DESIGN.md §3.4): a share c of the paths are
 * `uniform` paths whose line crosses no portal (lines that do are rejected: the portals' own) --
 * the light the portals cannot reach, reflected from outside or through unmarked openings. Their
 * weight is the uniform one over c; they are flagged FEN_PART_ESTIMATE_ONLY (part 1), so they
 * feed the strategy's statistics, not the image; the portal paths (part 0) weigh 1 / (1 - c) more.
 * Build with -DFEN_BVH_WIDTH (the portals' BVH has the scene's layout).
 */
#ifndef FEN_EMIT_PORTAL_H
#define FEN_EMIT_PORTAL_H

#include "lib/bvh_traverse.h"
#include "lib/emit_source.h"

typedef struct {
    const global float4* groups;      /* xyz unit normal, w area (m^2) */
    const global uint* group_alias;   /* per direction bin: an alias table over the groups */
    const global float* group_ratio;  /* per bin and group: A_g / P(g | bin) */
    const global uint* range;         /* per group: first triangle, count */
    const global ulong* triangle_cdf; /* group g: entries [first + g, first + g + count] */
    const global float4* vertices;    /* 3 per triangle */
    const global BvhNode* nodes;      /* the portal triangles' own BVH */
    const global TriPacket4* packets;
    uint group_count;
    uint group_alias_shift;
} Portals;

typedef struct {
    SourceTable sources;
    Sky sky;
    const global uint* cell_bin;  /* per sky cell: its direction bin (bin 0: the sun) */
    Portals portals;
    const global PortalParams* portal_params;
    SourceTable uniform_sources;  /* the complement's: `uniform`'s table and sky weights */
    Sky uniform_sky;
} PortalEmitter;

/* The strategy's kernel arguments after (params, counters, paths), and how kernels/emit_*.cl assemble
   them. */
#define FEN_PORTAL_ARGS                                                                          \
    global const SourceParams *source_params, global const uint *source_alias,                   \
        global const float *sky_theta, global const float *sky_phi, global const float *sky_values, \
        global const float *sky_factor, global const PortalParams *portal_params,                \
        global const float4 *portal_groups, global const uint *portal_group_alias,              \
        global const float *portal_group_ratio, global const uint *portal_cell_bin,              \
        global const uint *portal_range,                                                         \
        global const ulong *portal_cdf, global const float4 *portal_vertices,                    \
        global const BvhNode *portal_nodes, global const TriPacket4 *portal_packets,              \
        global const SourceParams *uniform_params, global const uint *uniform_alias,             \
        global const float *uniform_factor
#define FEN_PORTAL_EMITTER                                                                       \
    portal_emitter(params, source_params, source_alias, sky_theta, sky_phi, sky_values,          \
                   sky_factor, portal_params, portal_groups, portal_group_alias,                 \
                   portal_group_ratio, portal_cell_bin, portal_range, portal_cdf,                \
                   portal_vertices, portal_nodes, portal_packets, uniform_params, uniform_alias, \
                   uniform_factor)

static inline Portals portals_from(const global float4* groups, const global uint* group_alias,
                                   const global float* group_ratio, const global uint* range,
                                   const global ulong* triangle_cdf, const global float4* vertices,
                                   const global BvhNode* nodes, const global TriPacket4* packets,
                                   uint group_count, uint group_alias_shift)
{
    Portals p;
    p.groups = groups;
    p.group_alias = group_alias;
    p.group_ratio = group_ratio;
    p.group_alias_shift = group_alias_shift;
    p.range = range;
    p.triangle_cdf = triangle_cdf;
    p.vertices = vertices;
    p.nodes = nodes;
    p.packets = packets;
    p.group_count = group_count;
    return p;
}

static inline PortalEmitter portal_emitter(
    const global RenderParams* params, const global SourceParams* source_params,
    const global uint* source_alias, const global float* sky_theta, const global float* sky_phi,
    const global float* sky_values, const global float* sky_factor,
    const global PortalParams* portal_params, const global float4* portal_groups,
    const global uint* portal_group_alias, const global float* portal_group_ratio,
    const global uint* portal_cell_bin, const global uint* portal_range, const global ulong* portal_cdf,
    const global float4* portal_vertices, const global BvhNode* portal_nodes,
    const global TriPacket4* portal_packets, const global SourceParams* uniform_params,
    const global uint* uniform_alias, const global float* uniform_factor)
{
    PortalEmitter e;
    e.sources.params = source_params;
    e.sources.alias = source_alias;
    e.sky = sky_from(sky_theta, sky_phi, sky_values, sky_factor, params->sky_theta_nodes,
                     params->sky_phi_nodes);
    e.cell_bin = portal_cell_bin;
    e.portals = portals_from(portal_groups, portal_group_alias, portal_group_ratio, portal_range,
                             portal_cdf, portal_vertices, portal_nodes, portal_packets,
                             portal_params->groups, portal_params->group_alias_shift);
    e.portal_params = portal_params;
    e.uniform_sources.params = uniform_params;
    e.uniform_sources.alias = uniform_alias;
    e.uniform_sky = sky_from(sky_theta, sky_phi, sky_values, uniform_factor, params->sky_theta_nodes,
                             params->sky_phi_nodes);
    return e;
}

/* Uniform on portal triangle t from two uniforms. */
static inline float3 portal_point(const Portals* portals, uint t, float u1, float u2)
{
    const float su = sqrt(u1);
    const float b1 = su * (1.0f - u2), b2 = su * u2;
    const float3 p0 = portals->vertices[3 * t].xyz, p1 = portals->vertices[3 * t + 1].xyz,
                 p2 = portals->vertices[3 * t + 2].xyz;
    return p0 + b1 * (p1 - p0) + b2 * (p2 - p0);
}

/* Index i in [0, n) with cdf[i] <= r < cdf[i+1] for an integer CDF of n + 1 entries (binary:
   a group has few triangles, or the table would be large anyway). */
static inline uint cdf_search_binary(const global ulong* cdf, uint n, uint r)
{
    uint lo = 0, hi = n;
    while (hi - lo > 1) {
        const uint mid = (lo + hi) >> 1;
        if (cdf[mid] <= (ulong)r)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* eq. (1), averaged over direction bin `bin`: a portal triangle for direction `dir` -- a group from
   the bin's alias table (exact integer probabilities P(g | bin), > 0 for every group), then a
   triangle of it by area, exact likewise. *scale = A_g |dir.n_g| / P(g | bin), what the weight
   carries for the portals (host/emission/portal_emission.h). FEN_INVALID_ID when the group drawn
   is edge-on to dir (it carries no light along dir). */
static inline uint portal_pick_triangle(const Portals* portals, uint bin, float3 dir, uint r_group,
                                        uint r_tri, float* scale)
{
    const uint columns = 1u << (32u - portals->group_alias_shift);
    const uint g = alias_pick(portals->group_alias + 2u * bin * columns, portals->group_alias_shift, r_group);
    *scale = fabs(dot(dir, portals->groups[g].xyz)) * portals->group_ratio[bin * portals->group_count + g];
    if (!(*scale > 0.0f))
        return FEN_INVALID_ID;
    const uint first = portals->range[2 * g], count = portals->range[2 * g + 1];
    return first + cdf_search_binary(portals->triangle_cdf + first + g, count, r_tri);
}

/* A complement path (a share c of all): `uniform` emission, rejected when its line crosses a portal;
   weight over c; flagged for the statistics only. */
static inline int emit_portal_complement(const global RenderParams* params, const PortalEmitter* e, ulong path,
                                         RngBlock bits, float share, PathState* p)
{
    float3 dir, weight;
    const float3 origin = uniform_line(params, &e->uniform_sources, &e->uniform_sky, path, bits, &dir, &weight);
    const RayPre r = ray_setup(origin, dir, 0.0f, INFINITY, FEN_BVH_WIDTH);
    if (bvh_intersect_any(e->portals.nodes, e->portals.packets, &r))
        return 0;
    p->org = (float4)(origin, 0.0f);
    p->dir = (float4)(dir, 0.0f);
    p->beta = (float4)(weight / share, as_float(FEN_PART_ESTIMATE_ONLY | 1u));
    return 1;
}

/* Fills *p with a new path; returns 0 when the candidate is rejected (overlap) or carries no light. */
static inline int emit_portal(const global RenderParams* params, const PortalEmitter* e, ulong path,
                              PathState* p)
{
    path_start(p, path);
    const RngBlock bits = rng_path_bits(params->seed, p->path_lo, p->path_hi, 0, FEN_RNG_EMIT);
    const RngBlock bits2 = rng_path_bits(params->seed, p->path_lo, p->path_hi, 0, FEN_RNG_EMIT_PORTAL);
    const float4 u2 = rng_unit24x4(bits2.y, bits2.z, bits2.w);
    const float complement = e->portal_params->complement;
    if (complement > 0.0f && u2.w < complement)
        return emit_portal_complement(params, e, path, bits, complement, p);

    const uint shift = e->sources.params->alias_shift;
    const uint entry = alias_pick(e->sources.alias, shift, emission_pick_bits(params, path, bits.x, shift));
    float3 beta;
    const float3 dir = source_direction(params, &e->sky, e->sources.params, entry,
                                        fen_u32_to_unit(bits.z), fen_u32_to_unit(bits.w), &beta);
    float scale;
    const uint bin = entry == 0 ? 0u : e->cell_bin[entry - 1];
    const uint t = portal_pick_triangle(&e->portals, bin, dir, bits.y, bits2.x, &scale);
    if (t == FEN_INVALID_ID)
        return 0;
    const float3 origin = origin_outside(params, portal_point(&e->portals, t, u2.x, u2.y), dir);

    beta *= scale;
    const uint overlap = e->portal_params->overlap;
    if (overlap != FEN_OVERLAP_NONE) {
        /* overlap: N(x, v) portal triangles on the line */
        const RayPre r = ray_setup(origin, dir, 0.0f, INFINITY, FEN_BVH_WIDTH);
        const uint n = max(bvh_count_hits(e->portals.nodes, e->portals.packets, &r), 1u);
        if (overlap == FEN_OVERLAP_WEIGHT)
            beta /= (float)n;
        else if (u2.z * (float)n >= 1.0f)
            return 0;
    }

    if (complement > 0.0f)
        beta /= 1.0f - complement;
    p->org = (float4)(origin, 0.0f);
    p->dir = (float4)(dir, 0.0f);
    p->beta = (float4)(beta, 0.0f);
    return 1;
}

#endif /* FEN_EMIT_PORTAL_H */
