/* sky.h — the sky's luminance on the device, and sampling a direction from it
 * (DESIGN.md §1 "Sky", §3.1 `uniform` emission).
 *
 * The goniogram g is tabulated at (theta, phi) nodes (radians; theta from the zenith, phi from
 * north towards east), bilinear inside a cell, zero below the horizon; the direction towards the
 * sky at (theta, phi) is (sin t sin p, cos t, -sin t cos p). Sampling: a cell with the probability
 * P_k = (cdf[k+1] - cdf[k]) / 2^32 (host: about proportional to its integral of g sin(theta)),
 * then (theta, phi) in the
 * cell with density g_bilinear / B_k per d(theta) d(phi), B_k the cell's integral of g. The density
 * per steradian is then P_k g / (B_k sin theta), so a sky path's weight g / p is
 * factor[k] * sin(theta) with factor[k] = B_k / P_k -- exact for the procedure, whatever the grid.
 */
#ifndef FEN_SKY_H
#define FEN_SKY_H

#include "lib/sampling.h"

typedef struct {
    const global float* theta;   /* nt node zenith angles, increasing from 0 to pi/2 */
    const global float* phi;     /* np node azimuths, increasing from 0 to 2 pi */
    const global float* values;  /* nt x np luminances (cd/m^2), row-major by theta */
    const global ulong* cdf;     /* cells + 1 entries, 0 .. 2^32 */
    const global float* factor;  /* per cell: B_k / P_k */
    uint nt, np;
} Sky;

/* Largest i < n-1 with nodes[i] <= x (nodes increasing, n >= 2). */
static inline uint sky_node_search(const global float* nodes, uint n, float x)
{
    uint lo = 0, hi = n - 1;
    while (hi - lo > 1) {
        const uint mid = (lo + hi) >> 1;
        if (nodes[mid] <= x)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* Luminance arriving from direction `to_sky` (unit, pointing at the sky). */
static inline float sky_eval(const Sky* s, float3 to_sky)
{
    if (s->nt < 2 || to_sky.y <= 0.0f)
        return 0.0f;
    const float theta = acos(fmin(to_sky.y, 1.0f));
    float phi = atan2(to_sky.x, -to_sky.z);
    if (phi < 0.0f)
        phi += 2.0f * FEN_PI;
    const uint i = sky_node_search(s->theta, s->nt, theta);
    const uint j = sky_node_search(s->phi, s->np, phi);
    const float st = clamp((theta - s->theta[i]) / (s->theta[i + 1] - s->theta[i]), 0.0f, 1.0f);
    const float sp = clamp((phi - s->phi[j]) / (s->phi[j + 1] - s->phi[j]), 0.0f, 1.0f);
    const global float* row0 = s->values + i * s->np;
    const global float* row1 = row0 + s->np;
    return mix(mix(row0[j], row0[j + 1], sp), mix(row1[j], row1[j + 1], sp), st);
}

/* A direction towards the sky with the density above; *weight = factor[k] * sin(theta), the
   path weight per unit of (pi R^2 / P(sky)). */
static inline float3 sky_sample(const Sky* s, uint r_cell, float u_theta, float u_phi, float* weight)
{
    const uint cells = (s->nt - 1) * (s->np - 1);
    const uint k = cdf_search(s->cdf, cells, r_cell);
    const uint i = k / (s->np - 1), j = k % (s->np - 1);
    const global float* row0 = s->values + i * s->np;
    const global float* row1 = row0 + s->np;
    const float g00 = row0[j], g01 = row0[j + 1], g10 = row1[j], g11 = row1[j + 1];
    const float a = sample_linear(u_theta, g00 + g01, g10 + g11);
    const float b = sample_linear(u_phi, mix(g00, g10, a), mix(g01, g11, a));
    const float theta = mix(s->theta[i], s->theta[i + 1], a);
    const float phi = mix(s->phi[j], s->phi[j + 1], b);
    const float st = sin(theta);
    *weight = s->factor[k] * st;
    return (float3)(st * sin(phi), cos(theta), -st * cos(phi));
}

#endif /* FEN_SKY_H */
