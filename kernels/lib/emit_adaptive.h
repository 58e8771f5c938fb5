/* emit_adaptive.h — the `adaptive` emission strategy (DESIGN.md §3.3, the paper's method 2, eq. 7;
 * host half and the derivation: host/emission/adaptive_strategy.h).
 *
 * The host keeps a grid of cells over emitted rays (x, v) -- boxes of directions times boxes of
 * the origin's 2D parametrisation, refined where the light is -- with probabilities P(cell)
 * learned from the contributions of earlier paths, mixed with a defensive share of the base
 * density. Per path, one Philox block: 32 bits (or the batch's lattice: lib/emit_source.h) pick a
 * cell (integer alias table, exact P), 16 + 16
 * bits the direction in the cell's box (uniform in solid angle: cos(theta) = 1 - s, phi = 2 pi t;
 * s in [1, 2) is the ground's glow below the horizon, whose light travels upwards) or in the
 * sun's cone, 16 + 16 bits the origin in its box. Which sixteenth of the cell the path
 * fell in (its origin quarter and its direction quarter) rides along in beta.w, and connect.cl
 * adds the luminance of every contribution that reaches the camera (and its square) to that
 * part's statistics (paths are not counted: the host knows how many each part should get).
 *   - Disk cells (base `uniform`): the origin box is a piece of the unit square that the
 *     concentric map sends to the disk of radius R orthogonal to v (travel_basis, continuous in v).
 *     Density per area orthogonal to v: P(cell) / (pi R^2 |box|). Over a `portal` base, a disk path
 *     whose line crosses a portal is rejected: the portal cells emit those lines.
 *   - Portal cells (base `portal`): the box is a piece of a portal plane's frame (PortalFrame).
 *     Density per area of the plane: P(cell) / (A_frame |box|), so per area orthogonal to v it has
 *     |v.n| more. The candidate is kept only if the first portal its line crosses is the plane's
 *     triangle at x: each line is then generated through one crossing only (the overlap fix that
 *     works with unequal densities), and points of the frame outside the plane's triangles are
 *     rejected.
 * Weight: the emitted radiance over the density -- E cone (sun) or g(v) (sky, per steradian of the
 * box) times cell.weight = A_region |box| (Omega_box) / P(cell), times |v.n| in a portal cell. A
 * rejected candidate spends its path index (and counts in its cell): a path that carried nothing.
 * Build with -DFEN_BVH_WIDTH (the portals' BVH has the scene's layout).
 */
#ifndef FEN_EMIT_ADAPTIVE_H
#define FEN_EMIT_ADAPTIVE_H

#include "lib/bvh_traverse.h"
#include "lib/emit_source.h"

typedef struct {
    const global AdaptiveParams* params;
    const global uint* cell_alias;
    const global AdaptiveCell* cells;
    Sky sky;                       /* the scene's sky, evaluated (not sampled) */
    const global PortalFrame* frames;
    const global BvhNode* portal_nodes;
    const global TriPacket4* portal_packets;
} AdaptiveEmitter;

/* The strategy's kernel arguments after (params, counters, paths), and how kernels/emit_*.cl
   assemble them. Over a `uniform` base the portal buffers are placeholders, never read. */
#define FEN_ADAPTIVE_ARGS                                                                        \
    global const AdaptiveParams *adaptive_params, global const uint *cell_alias,                 \
        global const AdaptiveCell *cells, global const float *sky_theta,                         \
        global const float *sky_phi, global const float *sky_values,                             \
        global const PortalFrame *frames,                                                        \
        global const BvhNode *portal_nodes, global const TriPacket4 *portal_packets
#define FEN_ADAPTIVE_EMITTER                                                                     \
    adaptive_emitter(params, adaptive_params, cell_alias, cells, sky_theta, sky_phi, sky_values, \
                     frames, portal_nodes, portal_packets)

static inline AdaptiveEmitter adaptive_emitter(
    const global RenderParams* params, const global AdaptiveParams* adaptive_params,
    const global uint* cell_alias, const global AdaptiveCell* cells, const global float* sky_theta,
    const global float* sky_phi, const global float* sky_values, const global PortalFrame* frames, const global BvhNode* portal_nodes,
    const global TriPacket4* portal_packets)
{
    AdaptiveEmitter e;
    e.params = adaptive_params;
    e.cell_alias = cell_alias;
    e.cells = cells;
    e.sky = sky_from(sky_theta, sky_phi, sky_values, (const global float*)0, params->sky_theta_nodes,
                     params->sky_phi_nodes);
    e.frames = frames;
    e.portal_nodes = portal_nodes;
    e.portal_packets = portal_packets;
    return e;
}

/* Fills *p with a new path; returns 0 for a rejected candidate. */
static inline int emit_adaptive(const global RenderParams* params, const AdaptiveEmitter* e,
                                ulong path, PathState* p)
{
    path_start(p, path);
    const RngBlock bits = rng_path_bits(params->seed, p->path_lo, p->path_hi, 0, FEN_RNG_EMIT);
    const uint c = alias_pick(e->cell_alias, e->params->cell_alias_shift, emission_pick_bits(params, path, bits.x, e->params->cell_alias_shift));
    const global AdaptiveCell* cell = e->cells + c;
    const float4 box = cell->box, dirs = cell->dirs;
    const float2 ux = unit16x2(bits.z), uv = unit16x2(bits.y);
    const uint part = FEN_CELL_PARTS * c + (ux.x >= 0.5f ? 1u : 0u) + (ux.y >= 0.5f ? 2u : 0u) +
                      (uv.x >= 0.5f ? 4u : 0u) + (uv.y >= 0.5f ? 8u : 0u);
    p->beta = (float4)(0.0f, 0.0f, 0.0f, as_float(part)); /* what a rejected candidate leaves */

    float3 weight, dir;
    if (dirs.z == 0.0f) {
        dir = sun_direction(params, uv.x, uv.y);
        weight = e->params->sun_weight.xyz;
        if (params->openings_share > 0.0f) /* lib/opening_walk.h */
            p->flags |= FEN_PATH_SUN_KEPT;
    } else {
        /* uniform in the box of (s, t): cos(theta) = 1 - s, phi = 2 pi t (angles in units of pi
           for fen_sincospi) */
        const float2 st = dirs.xy + dirs.zw * uv;
        const float cos_t = 1.0f - st.x;
        const float sin_t = sqrt(fmax(0.0f, st.x * (2.0f - st.x)));
        const float phi = 2.0f * st.y;
        const float L = sky_eval_angles(&e->sky, fen_acos(cos_t), phi * FEN_PI);
        float cos_p;
        const float sin_p = fen_sincospi(phi, &cos_p);
        dir = -(float3)(sin_t * sin_p, cos_t, -sin_t * cos_p);
        weight = (float3)(L);
    }

    const float2 s = box.xy + box.zw * ux;
    float3 origin;
    if (cell->region == FEN_REGION_DISK) {
        float3 t1, t2;
        travel_basis(dir, &t1, &t2);
        origin = disk_ray_origin(params, dir, t1, t2, sample_disk_concentric(s.x, s.y));
        if (e->params->portal_base) {
            const RayPre r = ray_setup(origin, dir, 0.0f, INFINITY, FEN_BVH_WIDTH);
            if (bvh_intersect_any(e->portal_nodes, e->portal_packets, &r))
                return 0;
        }
    } else {
        const global PortalFrame* f = e->frames + (cell->region - 1);
        const float3 x = f->origin.xyz + s.x * f->axis_s.xyz + s.y * f->axis_t.xyz;
        origin = origin_outside(params, x, dir);
        /* the first portal on the line must be the plane's, at x (a little slack past x for the
           rounding of the origin: the plane is crossed once, so nothing else lies there) */
        const float tx = length(x - origin);
        const RayPre r = ray_setup(origin, dir, 0.0f, tx * 1.00001f + 1e-4f, FEN_BVH_WIDTH);
        const Hit h = bvh_intersect_closest(e->portal_nodes, e->portal_packets, &r);
        if (h.prim - as_uint(f->normal.w) >= f->triangles) /* also FEN_INVALID_ID: no portal */
            return 0;
        weight *= fabs(dot(dir, f->normal.xyz));
    }
    weight *= cell->weight;
    p->org = (float4)(origin, 0.0f);
    p->dir = (float4)(dir, 0.0f);
    p->beta = (float4)(weight, as_float(part));
    return 1;
}

#endif /* FEN_EMIT_ADAPTIVE_H */
