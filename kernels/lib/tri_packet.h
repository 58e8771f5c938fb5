/* tri_packet.h — watertight intersection of one ray with a TriPacket4 (four triangles at once).
 *
 * Woop, Benthin, Wald, "Watertight Ray/Triangle Intersection", JCGT 2(1) 2013, without the
 * double-precision fallback: the edge tests are inclusive (U, V, W >= 0 or all <= 0), so a ray
 * through a shared edge or vertex hits at least one of the neighbours, never none.
 * Why that holds in floating point: the edge function of a shared edge is computed from the same
 * sheared vertices with the operands mirrored, and fl(a*b - c*d) == -fl(c*d - a*b) exactly --
 * but only without fused multiply-add, hence FP_CONTRACT OFF below. Vertices are stored raw
 * (fen_bvh.h) so a shared vertex is the same number in both triangles.
 * Zero-area triangles never reach the device (bvh/bvh_build.cpp drops them); det == 0 (a ray in
 * the triangle's plane) is a miss.
 */
#ifndef FEN_TRI_PACKET_H
#define FEN_TRI_PACKET_H

#include "lib/ray_setup.h"

#pragma OPENCL FP_CONTRACT OFF

/* Per lane: hit distance, or +inf where the lane misses (tmin, tmax). b1/b2 are the barycentric
   weights of vertices 1 and 2. */
static inline float4 tri_packet_intersect(const global TriPacket4* p, const RayPre* r, float tmax,
                                          float4* b1_out, float4* b2_out)
{
    const global float* v = p->v;
    const float ox = fen_axis(r->org, r->kx), oy = fen_axis(r->org, r->ky),
                oz = fen_axis(r->org, r->kz);
    const float4 az = vload4(0, v + (0 + r->kz) * 4) - oz;
    const float4 bz = vload4(0, v + (3 + r->kz) * 4) - oz;
    const float4 cz = vload4(0, v + (6 + r->kz) * 4) - oz;
    const float4 ax = (vload4(0, v + (0 + r->kx) * 4) - ox) - r->sx * az;
    const float4 ay = (vload4(0, v + (0 + r->ky) * 4) - oy) - r->sy * az;
    const float4 bx = (vload4(0, v + (3 + r->kx) * 4) - ox) - r->sx * bz;
    const float4 by = (vload4(0, v + (3 + r->ky) * 4) - oy) - r->sy * bz;
    const float4 cx = (vload4(0, v + (6 + r->kx) * 4) - ox) - r->sx * cz;
    const float4 cy = (vload4(0, v + (6 + r->ky) * 4) - oy) - r->sy * cz;

    const float4 u = cx * by - cy * bx;
    const float4 w_ = bx * ay - by * ax;
    const float4 vv = ax * cy - ay * cx;
    const int4 neg = (u < 0.0f) | (vv < 0.0f) | (w_ < 0.0f);
    const int4 pos = (u > 0.0f) | (vv > 0.0f) | (w_ > 0.0f);
    const float4 det = u + vv + w_;
    const float4 tsc = u * (r->sz * az) + vv * (r->sz * bz) + w_ * (r->sz * cz);
    /* one division for t and both barycentrics */
    const float4 rcp = 1.0f / det;
    const float4 t = tsc * rcp;
    const int4 ok = ~(neg & pos) & (det != 0.0f) & (t > r->tmin) & (t < tmax);
    *b1_out = vv * rcp;
    *b2_out = w_ * rcp;
    return select((float4)(INFINITY), t, ok);
}

/* Lane k of a packet's per-lane results (t, b1, b2). */
static inline float fen_lane(float4 v, uint k)
{
    return k == 0u ? v.s0 : (k == 1u ? v.s1 : (k == 2u ? v.s2 : v.s3));
}

/* Smallest lane (lanes are finite or +inf, never NaN). */
static inline float tri_packet_min(float4 t)
{
    const float2 m = select(t.hi, t.lo, t.lo < t.hi);
    return m.x < m.y ? m.x : m.y;
}

#endif /* FEN_TRI_PACKET_H */
