/* ray_setup.h — per-ray constants that traversal and the triangle test reuse at every node.
 *
 * - Slab test: reciprocal direction with zeros replaced by a tiny signed value (never inf, so
 *   (lo - o) * idir is never 0 * inf = NaN), and for each axis the offset of the near and far
 *   plane inside a node's structure-of-arrays bounds (lo or hi depending on the direction's sign).
 * - Watertight triangle test (Woop, Benthin, Wald, JCGT 2013): kz = dominant axis of d, kx/ky
 *   the others (swapped when d[kz] < 0 to keep winding), and the shear Sx, Sy, Sz.
 * Device-only: these live in private memory, float3 is fine here.
 */
#ifndef FEN_RAY_SETUP_H
#define FEN_RAY_SETUP_H

#include "shared/fen_bvh.h"

typedef struct {
    float3 org;
    float3 idir;
    float tmin, tmax;
    /* slab planes: offsets (in floats) of the near/far plane arrays for x, y, z in a node of
       width W, whose bounds are lo_x hi_x lo_y hi_y lo_z hi_z (W floats each) */
    int near_x, near_y, near_z;
    int far_x, far_y, far_z;
    /* watertight test */
    int kx, ky, kz;
    float sx, sy, sz;
} RayPre;

/* 1/x per lane, with x = 0 treated as a tiny number of the same sign (-0 as negative), as one
   vector division (docs/bvh.md: with the shear's, two divisions per ray where PoCL made four). */
static inline float3 fen_safe_rcp3(float3 x)
{
    const float3 tiny = (float3)(1e-30f);
    return (float3)(1.0f) / select(copysign(tiny, x), x, isgreater(fabs(x), tiny));
}

static inline float fen_axis(float3 v, int k)
{
    return k == 0 ? v.x : (k == 1 ? v.y : v.z);
}

static inline RayPre ray_setup(float3 org, float3 dir, float tmin, float tmax, int width)
{
    RayPre r;
    r.org = org;
    r.tmin = tmin;
    r.tmax = tmax;
    r.idir = fen_safe_rcp3(dir);
    /* signbit, not d < 0: a direction of -0 must pick the same planes as its reciprocal's sign */
    const int sxn = signbit(r.idir.x) ? 1 : 0;
    const int syn = signbit(r.idir.y) ? 1 : 0;
    const int szn = signbit(r.idir.z) ? 1 : 0;
    r.near_x = (0 + sxn) * width;
    r.far_x = (1 - sxn) * width;
    r.near_y = (2 + syn) * width;
    r.far_y = (3 - syn) * width;
    r.near_z = (4 + szn) * width;
    r.far_z = (5 - szn) * width;

    const float ax = fabs(dir.x), ay = fabs(dir.y), az = fabs(dir.z);
    int kz = (ax >= ay) ? (ax >= az ? 0 : 2) : (ay >= az ? 1 : 2);
    int kx = kz == 2 ? 0 : kz + 1;
    int ky = kx == 2 ? 0 : kx + 1;
    const float dz = fen_axis(dir, kz);
    if (dz < 0.0f) {
        const int t = kx;
        kx = ky;
        ky = t;
    }
    r.kx = kx;
    r.ky = ky;
    r.kz = kz;
    /* the shear as one vector division too; dz is the dominant axis (|dz| > tiny for any
       direction but zero), so 1/dz is idir's lane kz, bit for bit */
    const float2 s = (float2)(fen_axis(dir, kx), fen_axis(dir, ky)) / (float2)(dz);
    r.sx = s.x;
    r.sy = s.y;
    r.sz = fen_axis(r.idir, kz);
    return r;
}

/* A ray as stored in a buffer (origin and tmin, direction and tmax). */
static inline RayPre ray_setup_stored(const global Ray* ray, int width)
{
    const float4 ot = ray->org_tmin, dt = ray->dir_tmax;
    return ray_setup(ot.xyz, dt.xyz, ot.w, dt.w, width);
}

#endif /* FEN_RAY_SETUP_H */
