/* opening_walk.h — light reflected outside, estimated from the openings' side (DESIGN.md §3.6,
 * --adaptive-openings-share).
 *
 * With adaptive emission and the opening aim (§3.5), a share S = RenderParams.openings_share of
 * the path indices (FEN_RNG_OPENING, depth 0, x < S) start on the aim's panes instead of at the
 * sky or the sun:
 *   - a triangle and side of the aim's panes by area times the side's learned weight (y), a point
 *     on it uniform in area and a cosine direction wo outwards (FEN_RNG_EMIT, depth 0);
 *   - L, the radiance arriving at the pane along -wo, by a walk traced outwards: at each diffuse
 *     vertex the sun by a next-event ray (anything, glass too, blocks it); the sky where the walk's
 *     own cosine look escapes (straight through the pane as well: its first look); glass met
 *     outside gives back its Fresnel reflection R of what arrives along the mirror direction (what
 *     it lets out from inside is the light paths'); Russian roulette by the albedo from the second
 *     diffuse vertex on; at most FEN_OPENING_WALK_MAX segments (a cut is bias, of order the
 *     albedo to that power);
 *   - the path then goes in from the pane along -wo with weight
 *         L T (1 - F) pi A_total / (A_t w_side) / S,
 *     (the point's density w_side / sum(A w), the cosine's cos / pi), depth 2 and FEN_PATH_BRANCHED:
 *     inside it is a light path that has bounced, with no emission cell: beta.w is one of the walks'
 *     own statistics parts (`part`, shared/fen_emission.h FEN_WALK_PARTS), which no cell learns from.
 * The other paths are light paths as ever, their weight over 1 - S. A light path whose first glass
 * is a listed pane side (opening_listed, a side of positive weight) ends there -- shade_path() --
 * unless FEN_PATH_SUN_KEPT: that light is the walks'. The two parts are disjoint and together
 * every path of light, so the image is unbiased: the walks take light that reached the pane after
 * a diffuse bounce outside (or by glass outside) and the sky seen through it; the light paths keep
 * the sun straight in, the sun by glass before any diffuse vertex, light through glass the aim does
 * not list, and light that entered and came out again.
 * Invariants: the aim's triangles are its panes' glass primitives (AimTriangle.normal.w); the
 * walks' random numbers (FEN_RNG_OPENING, FEN_RNG_WALK, FEN_RNG_EMIT at depth 0) are used by no
 * other step of the path, whose own start at depth 2.
 */
#ifndef FEN_OPENING_WALK_H
#define FEN_OPENING_WALK_H

#include "lib/emit_source.h"
#include "lib/fresnel.h"
#include "lib/opening_aim.h"
#include "lib/ray_offset.h"
#include "lib/sampling.h"
#include "lib/surface_hit.h"
#include "lib/texture.h"

#define FEN_OPENING_WALK_MAX 16u

/* What a walk needs of the scene. */
typedef struct {
    global const BvhNode* nodes;
    global const TriPacket4* packets;
    SurfaceMaterials sm;
    global const OpeningAim* aim;
} OpeningScene;

/* Whether the walks run now: a share is asked for and the aim lists panes (none in the first pass). */
static inline int opening_walks_on(global const RenderParams* params, global const OpeningAim* aim)
{
    return params->openings_share > 0.0f && aim->triangles != 0u;
}

/* Whether path `path` is one of the walks'. */
static inline int opening_walk_picked(global const RenderParams* params, global const OpeningAim* aim, ulong path,
                                      RngBlock* pick)
{
    if (!opening_walks_on(params, aim))
        return 0;
    *pick = rng_path_bits(params->seed, (uint)path, (uint)(path >> 32), 0, FEN_RNG_OPENING);
    return fen_u32_to_unit(pick->x) < params->openings_share;
}

static inline int opening_walk_blocked(const OpeningScene* s, float3 o, float3 d)
{
    const RayPre r = ray_setup(o, d, 0.0f, INFINITY, FEN_BVH_WIDTH);
    return bvh_intersect_any(s->nodes, s->packets, &r);
}

/* Fills *p with the path of index `path` starting inside at a listed pane side; returns 0 when it
   carries nothing. *rays counts the walk's rays. sun_weight: the sun's irradiance on a surface
   facing it (AdaptiveParams.sun_weight); part: the statistics part its contributions go to. */
static inline int opening_walk(global const RenderParams* params, const Sky* sky, float3 sun_weight, uint part,
                               const OpeningScene* s, ulong path, RngBlock pick, PathState* p, ulong* rays)
{
    global const OpeningAim* aim = s->aim;
    path_start(p, path);
    p->beta = (float4)(0.0f, 0.0f, 0.0f, as_float(part));
    float total = 0.0f;
    for (uint i = 0u; i < aim->triangles; ++i)
        total += aim->tri[i].p0.w * (fmax(aim->tri[i].e1.w, 0.0f) + fmax(aim->tri[i].e2.w, 0.0f));
    if (!(total > 0.0f))
        return 0;
    /* a triangle and side, 2 i + (0 front, 1 back), by area times the side's weight */
    float r = fen_u32_to_unit(pick.y) * total, chosen = 0.0f;
    uint k = 0u;
    for (uint j = 0u; j < 2u * aim->triangles; ++j) {
        const global AimTriangle* tj = aim->tri + j / 2u;
        const float wj = tj->p0.w * fmax((j & 1u) ? tj->e2.w : tj->e1.w, 0.0f);
        if (wj > 0.0f) {
            k = j;
            chosen = wj;
            if (r < wj)
                break;
        }
        r -= wj;
    }
    const global AimTriangle* t = aim->tri + k / 2u;
    const int front = (k & 1u) == 0u;
    const RngBlock b = rng_path_bits(params->seed, p->path_lo, p->path_hi, 0, FEN_RNG_EMIT);
    const float su = sqrt(fen_u32_to_unit(b.x)), v2 = fen_u32_to_unit(b.y);
    float pane_offset_m;
    const float3 p0 = t->p0.xyz;
    const float3 w = surface_point(p0, p0 + t->e1.xyz, p0 + t->e2.xyz, su * (1.0f - v2), su * v2, &pane_offset_m);
    const float3 ng = t->normal.xyz;
    const float3 n_out = front ? ng : -ng;
    const float3 wo = sample_cosine_hemisphere(n_out, fen_u32_to_unit(b.z), fen_u32_to_unit(b.w));
    const global DevMaterial* gm = s->sm.materials + s->sm.prim_material[as_uint(t->normal.w)];

    float3 L = (float3)(0.0f), throughput = (float3)(1.0f);
    float3 o = offset_ray_origin(w, pane_offset_m, ng, wo), d = wo;
    uint vertex = 0u; /* diffuse vertices met */
    for (uint i = 0u; i < FEN_OPENING_WALK_MAX; ++i) {
        *rays += 1;
        const SurfaceHit h = closest_surface(s->nodes, s->packets, o, d);
        if (as_uint(h.normal.w) == FEN_INVALID_ID) {
            L += throughput * (float3)(sky_eval(sky, d)); /* the sky (the sun's disc is the light paths') */
            break;
        }
        const uint prim = as_uint(h.normal.w);
        const global DevMaterial* m = s->sm.materials + s->sm.prim_material[prim];
        if (material_is_glass(m)) {
            const float cos_i = dot(d, h.normal.xyz);
            throughput *= fresnel_dielectric(cos_i, m->transmission.w);
            d = d - 2.0f * cos_i * h.normal.xyz;
            o = offset_ray_origin(h.pos.xyz, h.pos.w, h.normal.xyz, d);
            continue;
        }
        const float3 y = h.pos.xyz;
        const float3 n = dot(d, h.normal.xyz) < 0.0f ? h.normal.xyz : -h.normal.xyz;
        const float3 albedo = surface_albedo(&s->sm, m, prim, y);
        const RngBlock a = rng_path_bits(params->seed, p->path_lo, p->path_hi, vertex, FEN_RNG_WALK);
        const float3 to_sun = -sun_direction(params, fen_u32_to_unit(a.x), fen_u32_to_unit(a.y));
        const float cs = dot(n, to_sun);
        if (cs > 0.0f && (sun_weight.x > 0.0f || sun_weight.y > 0.0f || sun_weight.z > 0.0f)) {
            *rays += 1;
            if (!opening_walk_blocked(s, offset_ray_origin(y, h.pos.w, h.normal.xyz, to_sun), to_sun))
                L += throughput * albedo * sun_weight * (cs / FEN_PI);
        }
        throughput *= albedo;
        if (vertex >= 1u) {
            const float q = fmax(albedo.x, fmax(albedo.y, albedo.z));
            const RngBlock c = rng_path_bits(params->seed, p->path_lo, p->path_hi, 1u + vertex, FEN_RNG_OPENING);
            if (!(fen_u32_to_unit(c.x) < q))
                break;
            throughput /= q;
        }
        d = sample_cosine_hemisphere(n, fen_u32_to_unit(a.z), fen_u32_to_unit(a.w));
        o = offset_ray_origin(y, h.pos.w, h.normal.xyz, d);
        ++vertex;
    }
    if (!(L.x > 0.0f || L.y > 0.0f || L.z > 0.0f))
        return 0;
    const float3 in = -wo;
    const float3 trans = gm->transmission.xyz * (1.0f - fresnel_dielectric(dot(in, ng), gm->transmission.w));
    /* L cos over the density of the point (chosen / (total A_t)) and of the direction (cos / pi) */
    const float3 beta = L * (FEN_PI * t->p0.w * total / chosen) * trans * (1.0f / params->openings_share);
    p->org = (float4)(offset_ray_origin(w, pane_offset_m, ng, in), 0.0f);
    p->dir = (float4)(in, 0.0f);
    p->beta = (float4)(beta, as_float(part));
    p->depth = 2; /* as a light path that bounced once outside */
    p->flags |= FEN_PATH_BRANCHED | (FEN_PATH_OPENING_OTHER << FEN_PATH_OPENING_SHIFT);
    return 1;
}

#endif /* FEN_OPENING_WALK_H */
