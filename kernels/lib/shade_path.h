/* shade_path.h — what happens at a path's hit (DESIGN.md §2), for the wavefront's shade.cl and the
 * fused kernel (lib/fused_kernel.h) alike:
 *  - thin glass: specular reflection with probability R(theta) (Fresnel, one interface), else
 *    straight through with weight *= T (expected weight R + (1 - R) T, as the model says);
 *  - Lambertian (albedo rho from lib/texture.h: the factor, times the texture where there is one):
 *    connect to the pinhole -- if the camera sees this side of the surface, the
 *    contribution C = beta (rho/pi) |cos theta_x| / (d^2 A_pix cos^3 theta_c) goes into *c for
 *    lib/connect_path.h to test and splat -- then scatter cosine-weighted on the side the light
 *    arrived at. From interaction params->rr_depth on, Russian roulette: survive with probability
 *    q = max(rho), weight *= rho / q (its largest channel keeps its value); before it, every path
 *    goes on with weight *= rho (unbiased either way; which is more efficient: README "Path
 *    termination");
 *  - splitting (params->split_max > 1): at its first diffuse vertex, after the camera connection,
 *    a path of weight Y(beta) >= 2 split_weight goes on as k = min(floor(Y / split_weight),
 *    split_max) branches of weight beta / k each, scattered independently from the vertex. Branch 0
 *    goes on at once; when a branch ends, next_branch() starts the next from the vertex (kept in a
 *    SplitState), with its own random numbers (the branch number in the top byte of path_hi).
 *    Unbiased for any k: the branches' mean estimates what one path would. Where it pays: paths of
 *    large weight, which adaptive emission draws from cells it keeps near the base density --
 *    light that must bounce outside before it can enter (docs/results/house.md);
 *  - weight windows (guide->params->windows_at): at the first diffuse vertex the ratio of the path's
 *    weight to its slot's window splits (>= 2) or culls (< 1/2) it, in place of the fixed rule;
 *    with guide->params->window_later > 0, a path not split yet splits at any later diffuse
 *    vertex where its ratio to the slot's window, times window_later, is 2 or more (splitting
 *    only), its branches scattering as later vertices do. A path splits once at most
 *    (FEN_PATH_WAS_SPLIT), so one SplitState holds its waiting branches;
 *  - the guide (guide->params->slots > 0; lib/guide.h): at its first diffuse vertex, and for
 *    every branch of a split there, a path scatters through a leaf drawn from its slot's learned
 *    quadtree, its weight divided by the leaf's density; its later camera connections carry the
 *    record that feeds the table. With guide->params->every_vertex, every later diffuse vertex
 *    whose slot is learned draws from its table too (the record stays the first vertex's);
 *  - the opening aim (guide->aim->triangles > 0; lib/opening_aim.h, DESIGN.md §3.5): at every
 *    diffuse vertex of a path that has not passed glass yet, where a learned pane can be aimed at,
 *    one sample of the mixture of the cosine and a point on the panes, the weight over the
 *    mixture's density; it comes before the guide's table (the guide keeps its record). The first
 *    glass a path passes gives it its opening code (the aim's statistics), which a split keeps for
 *    every branch;
 *  - the openings' walks (params->openings_share > 0; lib/opening_walk.h, DESIGN.md §3.6): a light
 *    path whose first glass is a pane side the aim lists ends there unless FEN_PATH_SUN_KEPT (that
 *    light is the walks'), and the aim's mixture is off;
 *  - a path reaching params->max_depth interactions dies (counted, with its flux: a bias that is
 *    reported; the default cap is high enough that only endless paths meet it).
 * Invariant: the result depends only on the path, its hit, its split state, the guide's tables and
 * its random numbers (keyed by path index, branch and depth), never on which kernel or slot runs it.
 */
#ifndef FEN_SHADE_PATH_H
#define FEN_SHADE_PATH_H

#include "lib/accumulate.h"
#include "lib/camera.h"
#include "lib/fresnel.h"
#include "lib/guide.h"
#include "lib/opening_aim.h"
#include "lib/ray_offset.h"
#include "lib/rng.h"
#include "lib/sampling.h"
#include "lib/scene_access.h"
#include "lib/texture.h"

#if FEN_SPLIT_COUNT_MASK != ((1u << FEN_PATH_OPENING_SHIFT) - 1u)
#error "a split keeps the path's opening code in SplitState.count's bits from FEN_PATH_OPENING_SHIFT up"
#endif

/* The diffuse scatter on side n (unit) of a surface of albedo rho: Russian roulette from
   params->rr_depth on, else weight times rho; a cosine-weighted direction. Returns 1 with *next if
   the path goes on. */
static inline int scatter_diffuse(global const RenderParams* params, PathState* p, float3 albedo,
                                  float3 n, float4 u, float3* next)
{
    if (p->depth < params->rr_depth) {
        p->beta.xyz *= albedo;
        *next = sample_cosine_hemisphere(n, u.y, u.z);
        return albedo.x > 0.0f || albedo.y > 0.0f || albedo.z > 0.0f;
    }
    const float q = fmax(albedo.x, fmax(albedo.y, albedo.z));
    if (u.x < q) {
        p->beta.xyz *= albedo / q;
        *next = sample_cosine_hemisphere(n, u.y, u.z);
        return 1;
    }
    return 0;
}

/* What a work-item's paths did at their diffuse vertices, for FEN_CTR_DIFFUSE_VERTICES and
   FEN_CTR_GUIDED_VERTICES (the kernels add them to the counters once per work-item or group). */
typedef struct {
    ulong diffuse, guided;
    ulong split, culled; /* weight windows and --split: branches made; windows: paths culled */
} VertexTally;

/* With weight windows: the units of a path's arriving weight in the window statistics and the windows
   (lib/guide.h), luminance over A_pix at FEN_GUIDE_WINDOW_SCALE times the film's fixed-point scale;
   times Y(beta) it is comparable with the contributions the statistics sum at that scale. */
static inline float window_units(global const RenderParams* params, global const DevCamera* cam)
{
    return params->fixed_scale * FEN_GUIDE_WINDOW_SCALE / cam->up.w;
}

/* The point of the square for a diffuse scatter at a vertex of learned slot record r: drawn from
   the slot's table with the path's own guide random numbers (keyed by its depth, so every vertex
   draws its own); *key the leaf, *d its density (lib/guide.h). */
static inline float2 guide_draw(global const RenderParams* params, const Guide* guide, const PathState* p,
                                uint4 r, uint* key, float* d)
{
    const RngBlock bits = rng_path_bits(params->seed, p->path_lo, p->path_hi, p->depth + 1, FEN_RNG_GUIDE);
    return guide_sample(guide, r, bits, key, d);
}

/* scatter_diffuse() through point sq of the square, drawn with density d: the weight over d. */
static inline int scatter_through(global const RenderParams* params, PathState* p, float3 albedo, float3 n, float4 u,
                                  float2 sq, float d, float3* next)
{
    const int alive = scatter_diffuse(params, p, albedo, n, (float4)(u.x, sq.x, sq.y, u.w), next);
    p->beta.xyz /= d;
    return alive;
}

/* The point of the square the cosine hemisphere around n maps to unit direction v (v . n > 0): the
   inverse of sample_cosine_hemisphere(), for the guide's record of an aimed direction. */
static inline float2 cosine_square_of(float3 n, float3 v)
{
    float3 t1, t2;
    orthonormal_basis(n, &t1, &t2);
    const float a = dot(v, t1), b = dot(v, t2);
    float turn = 0.5f * atan2pi(b, a);
    turn = turn < 0.0f ? turn + 1.0f : turn;
    const float below1 = 0x1.fffffep-1f;
    return (float2)(fmin(a * a + b * b, below1), fmin(turn, below1));
}

/* The opening aim's scatter at x (side n) of a path still outside (lib/opening_aim.h): -1 when there
   is nothing to aim at from x (the caller scatters as it would without the aim); else whether the
   path goes on, *next and the weight as scatter_diffuse() leaves them times (cos / pi) over the
   mixture's density, *d_aim that density over the cosine's and *sq the direction's point of the
   cosine's square. At a path's first diffuse vertex (first), its flags say for the share's
   statistics that it drew from the mixture, and whether in the aim's region. */
static inline int scatter_aimed(global const RenderParams* params, const Guide* guide, PathState* p, float3 albedo,
                                float3 x, float3 n, float4 u, int first, float3* next, float* d_aim, float2* sq,
                                VertexTally* t)
{
    global const OpeningAim* aim = guide->aim;
    /* with the openings' walks the light the aim would send in is theirs (lib/opening_walk.h) */
    if (aim->triangles == 0u || path_opening(p->flags) != 0u || params->openings_share > 0.0f)
        return -1;
    float w[FEN_AIM_MAX_TRIS];
    const float total = aim_weights(aim, x, n, w);
    if (!(total > 0.0f))
        return -1;
    const float share = first ? aim->first_share : aim->cosine_share;
    *sq = u.yz;
    *d_aim = 1.0f;
    if (!scatter_diffuse(params, p, albedo, n, u, next))
        return 0;
    const RngBlock bits = rng_path_bits(params->seed, p->path_lo, p->path_hi, p->depth + 1, FEN_RNG_GUIDE);
    int aimed;
    float ratio;
    const float3 v = aim_mixture(aim, x, n, w, total, share, *next, bits, &aimed, &ratio);
    if (!(ratio > 0.0f))
        return 0;
    p->beta.xyz /= ratio;
    *next = v;
    *d_aim = ratio;
    /* at a first vertex, for the share's statistics: drawn by the mixture, and where the aim's part
       (1 - s) p_aim of the density passes the cosine's s p_cos, ratio = s + (1 - s) p_aim / p_cos */
    if (first)
        p->flags |= FEN_PATH_MIXED | (ratio > 2.0f * share ? FEN_PATH_AIM_REGION : 0u);
    if (aimed) {
        *sq = cosine_square_of(n, v);
        t->guided += 1;
    }
    return 1;
}

/* The diffuse scatter at a path's first diffuse vertex x (slot: its guide slot): by the opening aim
   when the path is still outside and something can be aimed at, else through a leaf of the guide's
   table when there is a guide, the weight over its density; with a guide, the record for what the
   path delivers from here on (lib/guide.h) -- for an aimed direction, its leaf and the density that
   makes the host's statistic right: the table's d(b) multiplies it there, so the record holds
   sqrt(d_aim d(b)) and (C g)^2 d(b) is the aim's own (C g_aim)^2 d_aim. Else scatter_diffuse(). */
static inline int scatter_first(global const RenderParams* params, const Guide* guide,
                                global const DevCamera* cam, PathState* p, float3 albedo, float3 x, float3 n,
                                float4 u, uint slot, float3* next, VertexTally* t,
                                volatile global ulong* counters)
{
    t->diffuse += 1;
    p->flags &= ~(FEN_PATH_MIXED | FEN_PATH_AIM_REGION); /* a branch may start here after a sibling */
    float d_aim;
    float2 sq;
    if (guide->params->slots == 0u) {
        const int aimed = scatter_aimed(params, guide, p, albedo, x, n, u, 1, next, &d_aim, &sq, t);
        return aimed >= 0 ? aimed : scatter_diffuse(params, p, albedo, n, u, next);
    }
    uint key;
    float d = 1.0f;
    const uint4 r = guide_record_of(guide, slot);
    if (guide->params->windows_at)
        guide_arrive(guide, slot, rgb_luminance(p->beta.xyz) * window_units(params, cam), counters);
    int alive = scatter_aimed(params, guide, p, albedo, x, n, u, 1, next, &d_aim, &sq, t);
    if (alive >= 0) {
        key = guide_leaf(guide, r, sq);
        d = sqrt(d_aim * guide_leaf_density(guide, key));
    } else {
        sq = u.yz;
        if (r.w & FEN_GUIDE_LEARNED) {
            sq = guide_draw(params, guide, p, r, &key, &d);
            t->guided += 1;
        } else {
            key = guide_leaf(guide, r, sq);
        }
        alive = scatter_through(params, p, albedo, n, u, sq, d, next);
    }
    const float y = rgb_luminance(p->beta.xyz);
    p->org.w = alive && y > 0.0f ? guide->params->stats_scale * cam->up.w / (y * d) : 0.0f;
    p->dir.w = as_float(key);
    return alive;
}

/* The diffuse scatter at a later diffuse vertex x (side n): through the guide's table where
   guide->params->every_vertex is set and x's slot is learned -- the importance a table holds belongs
   to the place and direction, not to the bounce that reached them -- the weight over its density;
   else scatter_diffuse(). The path's record stays its first vertex's: learning is unchanged. */
static inline int scatter_later(global const RenderParams* params, const Guide* guide, PathState* p,
                                float3 albedo, float3 x, float3 n, float4 u, float3* next, VertexTally* t)
{
    t->diffuse += 1;
    float d_aim;
    float2 sq;
    const int aimed = scatter_aimed(params, guide, p, albedo, x, n, u, 0, next, &d_aim, &sq, t);
    if (aimed >= 0)
        return aimed;
    if (guide->params->every_vertex && guide->params->slots) {
        const uint4 r = guide_record_of(guide, guide_slot(guide, x, n));
        if (r.w & FEN_GUIDE_LEARNED) {
            uint key;
            float d;
            const float2 sq = guide_draw(params, guide, p, r, &key, &d);
            t->guided += 1;
            return scatter_through(params, p, albedo, n, u, sq, d, next);
        }
    }
    return scatter_diffuse(params, p, albedo, n, u, next);
}

/* Splits path *p at vertex x (side n, primitive prim) into k >= 2 branches of weight beta / k: the
   first goes on from here, the rest wait in *s for next_branch(). tag: the vertex's guide slot at a
   first vertex, FEN_SPLIT_LATER at a later one. */
static inline void split_path(PathState* p, SplitState* s, float3 x, float offset_m, float3 n, uint prim, uint k,
                              uint tag, VertexTally* t)
{
    t->split += k;
    p->beta.xyz /= (float)k;
    s->pos = (float4)(x, offset_m);
    s->normal = (float4)(n, as_float(prim));
    s->beta = (float4)(p->beta.xyz, as_float(tag));
    s->depth = p->depth;
    s->next = 1u;
    s->count = k | (p->flags & ~FEN_SPLIT_COUNT_MASK); /* the opening code (FEN_PATH_OPENING_SHIFT) */
    s->path_hi = p->path_hi;
    p->flags |= FEN_PATH_SPLIT | FEN_PATH_WAS_SPLIT;
}

/* With weight windows: the ratio of the path's weight to window w (> 0) of the slot it is at. */
static inline float window_ratio(global const RenderParams* params, global const DevCamera* cam, const PathState* p,
                                 float w)
{
    return rgb_luminance(p->beta.xyz) * window_units(params, cam) / w;
}

/* After the interaction at x: the depth count, the cap on it, and the next ray. Returns alive. */
static inline int leave_vertex(global const RenderParams* params, PathState* p, float3 x, float offset_m,
                               float3 ng, float3 next, int alive, volatile global ulong* counters)
{
    p->depth += 1;
    if (alive && p->depth >= params->max_depth) {
        /* the cap guards against endless paths; what it removes is measured (rare: direct atomics) */
        alive = 0;
        counter_add(counters, FEN_CTR_MAX_DEPTH, 1);
        const float y = rgb_luminance(p->beta.xyz);
        fixed_add128(counters + FEN_CTR_CUT_FLUX_LO, y * params->fixed_scale);
    }
    if (!alive)
        return 0;
    p->org = (float4)(offset_ray_origin(x, offset_m, ng, next), p->org.w); /* w: the guide's record */
    p->dir = (float4)(next, p->dir.w);
    return 1;
}

/* Shades path *p at hit *h (a surface, not a miss). Sets *c to the camera connection, its pixel
   FEN_INVALID_ID when there is none; may split the path (*s). Returns 1 if the path goes on, with
   its next ray in *p. */
static inline int shade_path(global const RenderParams* params, const Guide* guide, PathState* p,
                             const SurfaceHit* h, const SurfaceMaterials* sm,
                             global const DevCamera* cam, Connection* c, SplitState* s,
                             VertexTally* t, volatile global ulong* counters)
{
    c->org.w = as_float(FEN_INVALID_ID);
    const uint prim = as_uint(h->normal.w);
    const global DevMaterial* m = sm->materials + sm->prim_material[prim];
    const float3 ng = h->normal.xyz;
    const float offset_m = h->pos.w;
    const float3 x = h->pos.xyz;
    const float3 dir = p->dir.xyz;
    const float4 u = rng_path(params->seed, p->path_lo, p->path_hi, p->depth + 1, FEN_RNG_SCATTER);
    float3 next = dir;
    int alive = 1;

    if (material_is_glass(m)) {
        const float cos_i = dot(dir, ng);
        if (u.x < fresnel_dielectric(cos_i, m->transmission.w)) {
            next = dir - 2.0f * cos_i * ng;
            p->flags |= FEN_PATH_REFLECTED;
        } else {
            next = dir;
            p->beta.xyz *= m->transmission.xyz;
            /* with the openings' walks, a light path whose first glass is a listed pane side ends there
               unless it is a sun path they cannot see: that light is theirs (lib/opening_walk.h) */
            if (params->openings_share > 0.0f && path_opening(p->flags) == 0u && !(p->flags & FEN_PATH_SUN_KEPT) &&
                opening_listed(guide->aim, prim, dir))
                alive = 0;
            else /* the first glass it passes: the opening it entered by, and its statistics */
                p->flags = opening_enter(guide->aim, guide->opening_prims, guide->opening_stats, p->flags, prim, dir,
                                         ng, p->beta.xyz, window_units(params, cam));
        }
    } else {
        /* the side of the surface the light arrived at */
        const float3 n = dot(dir, ng) < 0.0f ? ng : -ng;
        const float3 albedo = surface_albedo(sm, m, prim, x);
        float cos_c, dist2;
        const uint pixel = camera_project(cam, x, &cos_c, &dist2);
        if (pixel != FEN_INVALID_ID) {
            const float3 to_cam = cam->position.xyz - x;
            const float cos_x = dot(to_cam, n) / sqrt(dist2);
            if (cos_x > 0.0f) {
                const float3 value = p->beta.xyz * albedo * (cos_x / (FEN_PI * dist2 * cam->up.w *
                                                                       cos_c * cos_c * cos_c));
                if (value.x > 0.0f || value.y > 0.0f || value.z > 0.0f) {
                    const float3 o = offset_ray_origin(x, offset_m, ng, to_cam);
                    c->org = (float4)(o, as_float(pixel));
                    c->to_cam = (float4)(cam->position.xyz - o, as_float(opening_connection_word(p->flags)));
                    c->value = (float4)(value, p->beta.w); /* the emission cell */
                    /* z: the window statistics' scale, 0 without windows; w: the first vertex's
                       slot and power for them (a record, g > 0, names a leaf of the tables) */
                    const int windows = guide->params->windows_at && p->org.w > 0.0f;
                    c->guide = (float4)(p->org.w, p->dir.w,
                                        windows ? params->fixed_scale * FEN_GUIDE_WINDOW_SCALE : 0.0f,
                                        as_float(windows ? guide_window_word(guide, as_uint(p->dir.w)) : 0u));
                }
            }
        }
        if (p->flags & FEN_PATH_BRANCHED) {
            /* weight windows past the first vertex: the light that got in after bouncing outside
               is heavy only once it is in (docs/DESIGN.md §3.4) */
            /* a/w <= a/window_min for every window w: under 2 there, the path splits at no slot */
            const float later = guide->params->window_later;
            if (later > 0.0f && !(p->flags & FEN_PATH_WAS_SPLIT) &&
                later * window_ratio(params, cam, p, guide->params->window_min) >= 2.0f) {
                const float w = guide_window(guide, guide_slot(guide, x, n));
                const float ratio = w > 0.0f ? later * window_ratio(params, cam, p, w) : 0.0f;
                if (ratio >= 2.0f)
                    split_path(p, s, x, offset_m, n, prim, (uint)fmin(ratio, (float)guide->params->window_split_max),
                               FEN_SPLIT_LATER, t);
            }
            alive = scatter_later(params, guide, p, albedo, x, n, u, &next, t);
        } else {
            /* the first diffuse vertex: where a path may split, and where the guide steers; a sun path
               glass has not reflected is the openings' walks' from here (FEN_PATH_SUN_KEPT) */
            p->flags |= FEN_PATH_BRANCHED;
            if (!(p->flags & FEN_PATH_REFLECTED))
                p->flags &= ~FEN_PATH_SUN_KEPT;
            const uint slot = guide->params->slots ? guide_slot(guide, x, n) : 0u;
            /* weight windows: the path's weight against its slot's window w, where the slot has one */
            const float w = guide->params->slots ? guide_window(guide, slot) : 0.0f;
            uint k = 0u;
            if (w > 0.0f) {
                const float ratio = window_ratio(params, cam, p, w);
                if (ratio >= 2.0f) {
                    k = (uint)fmin(ratio, (float)guide->params->window_split_max);
                } else if (ratio < 0.5f) {
                    /* below the window: survives with probability q, weight over q (unbiased) */
                    const float q = fmax(ratio, guide->params->window_min_survival);
                    const float4 v = rng_path(params->seed, p->path_lo, p->path_hi, p->depth + 1, FEN_RNG_WINDOW);
                    if (v.x >= q) {
                        t->culled += 1;
                        return leave_vertex(params, p, x, offset_m, ng, next, 0, counters);
                    }
                    p->beta.xyz /= q;
                }
            } else if (params->split_max > 1u && !(as_uint(p->beta.w) & FEN_PART_ESTIMATE_ONLY)) {
                /* not the portal complement's estimate-only paths: what they measure needs no precision */
                const float y = rgb_luminance(p->beta.xyz);
                k = (uint)fmin(y / params->split_weight, (float)params->split_max);
            }
            if (k >= 2u)
                split_path(p, s, x, offset_m, n, prim, k, slot, t);
            alive = scatter_first(params, guide, cam, p, albedo, x, n, u, slot, &next, t, counters);
        }
    }
    return leave_vertex(params, p, x, offset_m, ng, next, alive, counters);
}

/* When a branch of a split path ends (a miss, roulette, the cap): starts the next branch waiting in
   *s, if any -- the scatter at the split vertex with the branch's own random numbers, as a first
   vertex scatters (guided, a new record) or, split later, as a later one (the record kept: nothing
   since the split has changed it). Returns 1 with its first ray in *p, 0 when no branch is left. */
static inline int next_branch(global const RenderParams* params, const Guide* guide, PathState* p,
                              SplitState* s, const SurfaceMaterials* sm, global const DevCamera* cam,
                              VertexTally* t, volatile global ulong* counters)
{
    while (p->flags & FEN_PATH_SPLIT) {
        const uint b = s->next++;
        if (s->next >= (s->count & FEN_SPLIT_COUNT_MASK))
            p->flags &= ~FEN_PATH_SPLIT;
        /* the opening code it had at the split, not the last branch's */
        p->flags = (p->flags & FEN_SPLIT_COUNT_MASK) | (s->count & ~FEN_SPLIT_COUNT_MASK);
        p->path_hi = s->path_hi | (b << 24);
        p->depth = s->depth;
        p->beta.xyz = s->beta.xyz;
        const float3 x = s->pos.xyz, n = s->normal.xyz;
        const uint prim = as_uint(s->normal.w);
        const float3 albedo = surface_albedo(sm, sm->materials + sm->prim_material[prim], prim, x);
        const float4 u = rng_path(params->seed, p->path_lo, p->path_hi, p->depth + 1, FEN_RNG_SCATTER);
        float3 next = n;
        const uint tag = as_uint(s->beta.w);
        const int alive = tag == FEN_SPLIT_LATER
                              ? scatter_later(params, guide, p, albedo, x, n, u, &next, t)
                              : scatter_first(params, guide, cam, p, albedo, x, n, u, tag, &next, t, counters);
        if (leave_vertex(params, p, x, s->pos.w, n, next, alive, counters)) {
            p->flags |= FEN_PATH_ALIVE;
            return 1;
        }
    }
    return 0;
}

#endif /* FEN_SHADE_PATH_H */
