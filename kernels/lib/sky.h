/* sky.h — the sky's luminance on the device, and sampling a direction from it
 * (DESIGN.md §1 "Sky", §3.1 `uniform` emission).
 *
 * The goniogram g is tabulated at (theta, phi) nodes (radians; theta from the zenith, phi from
 * north towards east), bilinear inside a cell; the direction towards the sky at (theta, phi) is
 * (sin t sin p, cos t, -sin t cos p). Its theta nodes end at pi/2 (zero below the horizon), or,
 * with the ground's glow, at pi: the node pi/2 then appears twice, the sky's horizon row and the
 * ground's (host/sky/goniogram.h), and the zero-width cell between them is never drawn (its
 * integral, and so its probability, is 0) nor looked up (a lookup at pi/2 lands on the ground's
 * row: every direction with y <= 0 reads the ground). Sampling: a cell k chosen with some
 * probability P_k (lib/emit_uniform.h: the joint source table), then (theta, phi) in the
 * cell with density g_bilinear / B_k per d(theta) d(phi), B_k the cell's integral of g. The density
 * per steradian is then P_k g / (B_k sin theta), so a sky path's weight g / p is
 * factor[k] * sin(theta) with factor[k] = B_k / P_k -- exact for the procedure, whatever the grid.
 */
#ifndef FEN_SKY_H
#define FEN_SKY_H

#include "shared/fen_render.h"
#include "lib/sampling.h"

typedef struct {
    const global float* theta;   /* nt node zenith angles, non-decreasing from 0 to pi/2, or to pi with a ground */
    const global float* phi;     /* np node azimuths, increasing from 0 to 2 pi */
    const global float* values;  /* nt x np luminances (cd/m^2), row-major by theta */
    const global float* factor;  /* per cell: B_k / P_k */
    uint nt, np;
} Sky;

static inline Sky sky_from(const global float* theta, const global float* phi,
                          const global float* values, const global float* factor, uint nt, uint np)
{
    Sky s;
    s.theta = theta;
    s.phi = phi;
    s.values = values;
    s.factor = factor;
    s.nt = nt;
    s.np = np;
    return s;
}

/* Largest i < n-1 with nodes[i] <= x (nodes non-decreasing, n >= 2): never the first of two
   equal nodes below n-1, so never a zero-width cell. The search starts from x's bucket
   (shared/fen_render.h FEN_SKY_SEARCH_*): its bounds hold the answer for every x in the bucket,
   so it is the full search's, in a step or two where the full one took eight or nine (every sky
   path of adaptive emission makes two; a profile of the house put 11 % of its render there:
   docs/performance.md, "Where the device time goes"). */
static inline uint sky_node_search(const global float* nodes, uint n, float x)
{
    const global float* search = nodes + n;
    const uint buckets = as_uint(search[FEN_SKY_SEARCH_BUCKETS]);
    const float f = x * search[FEN_SKY_SEARCH_SCALE];
    const uint b = f > 0.0f ? min((uint)fmin(f, (float)buckets), buckets - 1u) : 0u; /* NaN: 0 */
    uint lo = as_uint(search[FEN_SKY_SEARCH_HINTS + 2u * b]), hi = as_uint(search[FEN_SKY_SEARCH_HINTS + 2u * b + 1u]);
    while (hi - lo > 1) {
        const uint mid = (lo + hi) >> 1;
        if (nodes[mid] <= x)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* Whether the table holds the ground's glow below the horizon (its last node is pi, not pi/2). */
static inline int sky_has_ground(const Sky* s)
{
    return s->nt >= 2 && s->theta[s->nt - 1] > 2.0f;
}

/* Luminance at zenith angle theta in [0, pi/2] (with a ground, [0, pi]) and azimuth phi in
   [0, 2 pi] (radians). */
static inline float sky_eval_angles(const Sky* s, float theta, float phi)
{
    if (s->nt < 2)
        return 0.0f;
    const uint i = sky_node_search(s->theta, s->nt, theta);
    const uint j = sky_node_search(s->phi, s->np, phi);
    const float st = clamp((theta - s->theta[i]) / (s->theta[i + 1] - s->theta[i]), 0.0f, 1.0f);
    const float sp = clamp((phi - s->phi[j]) / (s->phi[j + 1] - s->phi[j]), 0.0f, 1.0f);
    const global float* row0 = s->values + i * s->np;
    const global float* row1 = row0 + s->np;
    return mix(mix(row0[j], row0[j + 1], sp), mix(row1[j], row1[j + 1], sp), st);
}

/* Luminance arriving from direction `to_sky` (unit, pointing at the sky); below the horizon
   (y <= 0) the ground's glow, or 0 without one. */
static inline float sky_eval(const Sky* s, float3 to_sky)
{
    if (s->nt < 2 || (to_sky.y <= 0.0f && !sky_has_ground(s)))
        return 0.0f;
    const float theta = fen_acos(clamp(to_sky.y, -1.0f, 1.0f));
    float phi = atan2(to_sky.x, -to_sky.z);
    if (phi < 0.0f)
        phi += 2.0f * FEN_PI;
    return sky_eval_angles(s, theta, phi);
}

/* A direction towards the sky in cell k (below the horizon in a ground cell) with the density
   above; *weight = factor[k] sin(theta),
   the path weight per unit of the area the strategy's lines are drawn over (uniform: the box's
   silhouette). */
static inline float3 sky_sample(const Sky* s, uint k, float u_theta, float u_phi, float* weight)
{
    const uint i = k / (s->np - 1), j = k % (s->np - 1);
    const global float* row0 = s->values + i * s->np;
    const global float* row1 = row0 + s->np;
    const float g00 = row0[j], g01 = row0[j + 1], g10 = row1[j], g11 = row1[j + 1];
    const float a = sample_linear(u_theta, g00 + g01, g10 + g11);
    const float b = sample_linear(u_phi, mix(g00, g10, a), mix(g01, g11, a));
    /* angles in units of pi for fen_sincospi (lib/trig.h) */
    const float t = mix(s->theta[i], s->theta[i + 1], a) * (1.0f / FEN_PI);
    const float p = mix(s->phi[j], s->phi[j + 1], b) * (1.0f / FEN_PI);
    float ct, cp;
    const float st = fen_sincospi(t, &ct);
    const float sp = fen_sincospi(p, &cp);
    *weight = s->factor[k] * st;
    return (float3)(st * sp, ct, -st * cp);
}

#endif /* FEN_SKY_H */
