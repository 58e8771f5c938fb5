/* opening_aim.h — the opening aim on the device (DESIGN.md §3.5; layout: shared/fen_openings.h;
 * learning: host/scatter/opening_aim.h).
 *
 * Where a path crosses glass for the first time, after a diffuse bounce, it looks the primitive up
 * among the learned openings, keeps the opening side in its flags and adds its weight to that
 * side's statistics; its camera connections carry the code (Connection.to_cam.w) and add what
 * reaches the camera (lib/connect_path.h). A path straight from the sky is marked as in but not
 * counted: the aim never sends such light, and its share (the sun's patch on a floor) would
 * otherwise decide which opening looks important. At a diffuse vertex x of a path still outside, on side n, the aim draws a
 * direction by one sample of the mixture
 *     p(v) = s cos(v, n) / pi + (1 - s) sum_i P_i(x) q_i(x, v),
 * s the cosine share, P_i(x) = w_i / W triangle i's probability (w_i its weight from x's side times
 * area |cos| / d^2 at its centroid, zero behind n or behind the triangle's own side of zero
 * weight), q_i = t^2 / (area |cos|) the density of a uniform point on the triangle seen from x,
 * where the ray from x along v meets it at distance t (else 0).
 * Invariant: p(v) > 0 wherever cos(v, n) > 0, and the weight is times (cos / pi) / p(v): unbiased.
 */
#ifndef FEN_OPENING_AIM_H
#define FEN_OPENING_AIM_H

#include "shared/fen_openings.h"
#include "lib/accumulate.h"
#include "lib/rng.h"
#include "lib/sampling.h"

/* The opening side code in a path's flags: 0 outside, 2 j + side + 1, or FEN_PATH_OPENING_OTHER. */
static inline uint path_opening(uint flags)
{
    return flags >> FEN_PATH_OPENING_SHIFT;
}

/* The entry of primitive prim -- 2 j for opening j, plus 1 where the triangle faces against its pane
   -- or FEN_INVALID_ID: a binary search of the sorted (primitive, entry) pairs. */
static inline uint opening_of_prim(global const uint2* prims, uint n, uint prim)
{
    uint lo = 0u, hi = n;
    while (lo < hi) {
        const uint mid = (lo + hi) / 2u;
        const uint2 e = prims[mid];
        if (e.x == prim)
            return e.y;
        if (e.x < prim)
            lo = mid + 1u;
        else
            hi = mid;
    }
    return FEN_INVALID_ID;
}

/* A path of weight beta (after the glass) crosses glass primitive prim along dir, geometric normal
   ng: the first time, it takes a code -- after a diffuse bounce, of a learned opening: its side's,
   adding its weight (units: `units` per luminance) to that side's statistics; else
   FEN_PATH_OPENING_OTHER. Returns the path's new flags. */
static inline uint opening_enter(global const OpeningAim* aim, global const uint2* prims,
                                 volatile global ulong* stats, uint flags, uint prim, float3 dir, float3 ng,
                                 float3 beta, float units)
{
    if (path_opening(flags) != 0u)
        return flags;
    uint code = FEN_PATH_OPENING_OTHER;
    /* 2 j + 1 where the triangle's normal points against its pane's: sides are the pane's */
    const uint e = aim->prims && (flags & FEN_PATH_BRANCHED) ? opening_of_prim(prims, aim->prims, prim) : FEN_INVALID_ID;
    if (e != FEN_INVALID_ID) {
        code = (e & ~1u) + ((dot(dir, ng) < 0.0f ? 0u : 1u) ^ (e & 1u)) + 1u;
        volatile global ulong* s = stats + FEN_OPENING_STATS_WORDS * (ulong)(code - 1u);
        fixed_add128(s + FEN_OPENING_ENTERED_LO, rgb_luminance(beta) * units);
        atom_add(s + FEN_OPENING_ENTRIES, 1ul);
    }
    return flags | (code << FEN_PATH_OPENING_SHIFT);
}

/* The word a camera connection carries for the path (Connection.to_cam.w): its opening code, and
   how its first diffuse vertex scattered (FEN_OPENING_CONNECTION_MIXED, _AIM_REGION). */
static inline uint opening_connection_word(uint flags)
{
    return path_opening(flags) | ((flags & FEN_PATH_MIXED) ? FEN_OPENING_CONNECTION_MIXED : 0u) |
           ((flags & FEN_PATH_AIM_REGION) ? FEN_OPENING_CONNECTION_AIM_REGION : 0u);
}

/* Whether connection word `word` is of a path that entered a learned opening after a bounce. */
static inline int opening_learned(uint word)
{
    const uint code = word & 0xffu;
    return code != 0u && code != FEN_PATH_OPENING_OTHER;
}

/* A connection of luminance y (at the statistics' scale, `scale` per unit) that reached the camera,
   made by a path whose connection word (opening_connection_word) is `word`: added to the
   statistics of the opening side it entered by. */
static inline void opening_deliver(volatile global ulong* stats, uint word, float y, float scale)
{
    const uint code = word & 0xffu;
    if (!opening_learned(word) || !(y > 0.0f))
        return;
    fixed_add128(stats + FEN_OPENING_STATS_WORDS * (ulong)(code - 1u) + FEN_OPENING_DELIVERED_LO, y * scale);
}

/* Whether glass primitive prim, crossed along dir, is a pane side the aim lists: a triangle of
   positive weight on the side the path arrives from. With the openings' walks (lib/opening_walk.h)
   the light a path brings in there is theirs. */
static inline int opening_listed(global const OpeningAim* aim, uint prim, float3 dir)
{
    for (uint i = 0u; i < aim->triangles; ++i) {
        const global AimTriangle* t = aim->tri + i;
        if (as_uint(t->normal.w) == prim)
            return (dot(dir, t->normal.xyz) < 0.0f ? t->e1.w : t->e2.w) > 0.0f;
    }
    return 0;
}

/* Triangle i's weight w_i seen from x on side n (0 where it cannot be aimed at); returns W = sum. */
static inline float aim_weights(global const OpeningAim* aim, float3 x, float3 n, float* w)
{
    float total = 0.0f;
    for (uint i = 0u; i < aim->triangles; ++i) {
        const global AimTriangle* t = aim->tri + i;
        const float3 nt = t->normal.xyz;
        const float h = dot(x - t->p0.xyz, nt); /* > 0: x sees the front */
        const float side_weight = h > 0.0f ? t->e1.w : (h < 0.0f ? t->e2.w : 0.0f);
        const float3 d = t->p0.xyz + (t->e1.xyz + t->e2.xyz) * (1.0f / 3.0f) - x;
        const float d2 = dot(d, d);
        float wi = 0.0f;
        if (side_weight > 0.0f && dot(n, d) > 0.0f && d2 > 0.0f)
            wi = side_weight * t->p0.w * fabs(h) / (d2 * sqrt(d2));
        w[i] = wi;
        total += wi;
    }
    return total;
}

/* The triangles' part of the density (per sr) of direction v (unit) from x: sum P_i q_i. */
static inline float aim_pdf(global const OpeningAim* aim, float3 x, float3 v, const float* w, float total)
{
    float p = 0.0f;
    for (uint i = 0u; i < aim->triangles; ++i) {
        if (!(w[i] > 0.0f))
            continue;
        const global AimTriangle* t = aim->tri + i;
        /* Moller-Trumbore: x + s v = p0 + a e1 + b e2 */
        const float3 e1 = t->e1.xyz, e2 = t->e2.xyz;
        const float3 pv = cross(v, e2);
        const float det = dot(e1, pv);
        if (det == 0.0f)
            continue;
        const float inv = 1.0f / det;
        const float3 tv = x - t->p0.xyz;
        const float a = dot(tv, pv) * inv;
        const float3 qv = cross(tv, e1);
        const float b = dot(v, qv) * inv;
        const float s = dot(e2, qv) * inv;
        if (a >= 0.0f && b >= 0.0f && a + b <= 1.0f && s > 0.0f) {
            const float c = fabs(dot(v, t->normal.xyz));
            if (c > 0.0f)
                p += (w[i] / total) * s * s / (t->p0.w * c);
        }
    }
    return p;
}

/* Draws the aim's part: triangle i with probability w_i / W (bits.w), a uniform point on it
   (bits.y, bits.z); returns the unit direction from x to it. */
static inline float3 aim_draw(global const OpeningAim* aim, float3 x, const float* w, float total, RngBlock bits)
{
    float r = fen_u32_to_unit(bits.w) * total;
    uint k = FEN_INVALID_ID;
    for (uint i = 0u; i < aim->triangles; ++i) {
        if (!(w[i] > 0.0f))
            continue;
        k = i; /* the last with weight, should rounding leave r past every triangle */
        if (r < w[i])
            break;
        r -= w[i];
    }
    const global AimTriangle* t = aim->tri + k;
    const float su = sqrt(fen_u32_to_unit(bits.y)), v2 = fen_u32_to_unit(bits.z);
    const float3 y = t->p0.xyz + (su * (1.0f - v2)) * t->e1.xyz + (su * v2) * t->e2.xyz;
    return normalize(y - x);
}

/* One sample of the mixture at x (side n, unit), W = total > 0: `cosine`, a direction the caller drew
   from the cosine, with probability s (bits.x; the share, in (0, 1]), else aim_draw() (*aimed = 1).
   Returns the direction;
   *ratio = p(v) / (cos / pi), the factor the weight is divided by, or 0 where v lies below the
   surface (a point of a triangle partly behind it: nothing is sent that way). */
static inline float3 aim_mixture(global const OpeningAim* aim, float3 x, float3 n, const float* w, float total,
                                 float s, float3 cosine, RngBlock bits, int* aimed, float* ratio)
{
    *aimed = fen_u32_to_unit(bits.x) >= s;
    const float3 v = *aimed ? aim_draw(aim, x, w, total, bits) : cosine;
    const float c = dot(v, n);
    *ratio = 0.0f;
    if (c > 0.0f) {
        const float pc = c * (1.0f / FEN_PI);
        *ratio = (s * pc + (1.0f - s) * aim_pdf(aim, x, v, w, total)) / pc;
    }
    return v;
}

#endif /* FEN_OPENING_AIM_H */
