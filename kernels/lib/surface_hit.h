/* surface_hit.h — the next surface along a ray, as shade_path() needs it (point, offset for a
 * ray leaving it, unit geometric normal, primitive), for the wavefront's intersect.cl and the
 * fused kernel alike. The point and normal come from the triangle packet traversal has just
 * tested, still in cache (shade would otherwise fetch the triangle again: measured, 43 % of its
 * time on that miss). Requires lib/bvh_traverse.h (FEN_BVH_WIDTH).
 */
#ifndef FEN_SURFACE_HIT_H
#define FEN_SURFACE_HIT_H

#include "lib/bvh_traverse.h"
#include "lib/ray_offset.h"
#include "lib/scene_access.h"

/* The hit's triangle, read from the packet traversal has just tested. */
static inline void hit_triangle(global const TriPacket4* packets, uint packet_lane, float3* p0, float3* p1,
                                float3* p2)
{
    const global TriPacket4* p = packets + (packet_lane >> 2);
    const uint lane = packet_lane & 3u;
    *p0 = packet_vertex(p, lane, 0);
    *p1 = packet_vertex(p, lane, 1);
    *p2 = packet_vertex(p, lane, 2);
}

/* Whether the point of barycentrics (b0, b1, b2) lies within d_m of an edge of the triangle whose
   edge vectors are e1 = p1 - p0, e2 = p2 - p0 (c = their cross product): the distance to the edge
   opposite vertex i is b_i |c| / |edge i|, compared squared (no square roots on every hit). */
static inline int near_triangle_edge(float3 e1, float3 e2, float3 c, float b1, float b2, float d_m)
{
    const float b0 = 1.0f - b1 - b2;
    /* most hits are far from every edge, and one comparison says so: within d_m of an edge, that
       edge's barycentric is under d_m / altitude, so under 2^-8 where the altitude is 2^8 d_m or
       more (a few cm); in a narrower triangle the band narrows to altitude / 2^8, still far wider
       than t's rounding */
    if (fmin(b0, fmin(b1, b2)) >= 0x1p-8f)
        return 0;
    const float c2 = dot(c, c), d2 = d_m * d_m;
    const float3 e0 = e2 - e1;
    return b0 * b0 * c2 < d2 * dot(e0, e0) || b1 * b1 * c2 < d2 * dot(e2, e2) ||
           b2 * b2 * c2 < d2 * dot(e1, e1);
}

/* Whether triangle q0 q1 q2 lies in front of the plane through a of normal n (any length), on
   the side where sign(toward) > 0: every vertex in front or on the plane -- within 2^-12 of the
   farthest vertex's distance, so a vertex of a shared edge counts as on it after rounding -- and
   one more than d_m in front (a coplanar neighbour, the same surface, is not in front). A triangle
   reaching behind the plane (a floor running on under a wall standing on it) is not. */
static inline int triangle_in_front(float3 a, float3 n, float toward, float3 q0, float3 q1, float3 q2, float d_m)
{
    const float sgn = toward > 0.0f ? 1.0f : -1.0f;
    const float s0 = sgn * dot(q0 - a, n), s1 = sgn * dot(q1 - a, n), s2 = sgn * dot(q2 - a, n);
    const float hi = fmax(s0, fmax(s1, s2)), lo = fmin(s0, fmin(s1, s2));
    return hi > d_m * length(n) && lo >= -0x1p-12f * fmax(hi, -lo);
}

/* The next surface along the ray from org in direction dir (unit).
 * Where two surfaces meet at an angle (a wall standing on a floor, two meshes sharing the edge),
 * a ray reaching the edge from outside crosses both planes within the rounding of its t (about
 * 1e-6 m for a ray that started 10 m away; often the very same float): traversal may return the
 * one behind the other, by its inner side, and light started outside then lands inside a closed
 * room (measured: one such path of full weight held 99 % of the inner room's noise, and 6 % of
 * rays aimed within 2 micrometres of such an edge did it: tests/kernels/robustness_test.cpp). So
 * when the hit lies within 16 offsets of its triangle's edge (about 0.1 mm in a room), every
 * triangle the ray crosses within 2^-18 t + 16 offsets of the hit, before or after it, is a rival,
 * and a rival comes first if it lies wholly on the ray's side of the hit's plane (a wall met
 * before the floor it stands on), or the hit lies wholly beyond the rival's plane (a floor
 * whose edge meets a wall's face part way up, met through that wall). Either is decided by
 * triangle_in_front: vertices metres from the plane or on it, so the signs are sure where t's
 * order is not. A coplanar neighbour (the same surface) never displaces the hit, nor does a
 * triangle reaching to both sides of it (a floor running on under a wall standing on it: which
 * side of the wall the ray met the floor is as unsure as t, and the hit is kept).
 * Deterministic: the rivals are judged in the walk's fixed order. */
static inline SurfaceHit closest_surface(global const BvhNode* nodes, global const TriPacket4* packets,
                                         float3 org, float3 dir)
{
    const RayPre r = ray_setup(org, dir, 0.0f, INFINITY, FEN_BVH_WIDTH);
    uint packet_lane;
    Hit h = bvh_intersect_closest_at(nodes, packets, &r, &packet_lane);
    SurfaceHit s;
    if (h.prim == FEN_INVALID_ID) {
        s.pos = (float4)(0.0f);
        s.normal = (float4)(0.0f, 0.0f, 0.0f, as_float(FEN_INVALID_ID));
        return s;
    }
    float3 p0, p1, p2;
    hit_triangle(packets, packet_lane, &p0, &p1, &p2);
    float offset_m;
    float3 x = surface_point(p0, p1, p2, h.u, h.v, &offset_m);
    float3 c = cross(p1 - p0, p2 - p0);
    const float guard_m = 16.0f * offset_m; /* the first hit's, for every rival */
    if (near_triangle_edge(p1 - p0, p2 - p0, c, h.u, h.v, guard_m)) {
        const float reach = 0x1p-18f * h.t + guard_m;
        RayPre w = r;
        w.tmin = fmax(h.t - reach, 0.0f);
        w.tmax = h.t + reach;
        BvhWalk walk;
        bvh_walk_begin(&walk);
        for (uint leaf; (leaf = bvh_walk_next(&walk, nodes, &w)) != FEN_INVALID_ID;) {
            float4 b1, b2;
            const float4 t = tri_packet_intersect(packets + leaf, &w, w.tmax, &b1, &b2);
            for (uint lane = 0u; lane < 4u; ++lane) {
                const uint prim = packets[leaf].prim[lane];
                if (!(fen_lane(t, lane) < INFINITY) || prim == h.prim)
                    continue;
                float3 q0, q1, q2;
                hit_triangle(packets, leaf * 4u + lane, &q0, &q1, &q2);
                const float3 cq = cross(q1 - q0, q2 - q0);
                if (triangle_in_front(p0, c, dot(org - p0, c), q0, q1, q2, guard_m) ||
                    triangle_in_front(q0, cq, -dot(org - q0, cq), p0, p1, p2, guard_m)) {
                    /* the rival lies wholly on the ray's side of the hit's plane, or the hit wholly
                       beyond the rival's: the ray reached the rival first */
                    h.prim = prim;
                    h.u = fen_lane(b1, lane);
                    h.v = fen_lane(b2, lane);
                    p0 = q0;
                    p1 = q1;
                    p2 = q2;
                    c = cq;
                    x = surface_point(p0, p1, p2, h.u, h.v, &offset_m);
                }
            }
        }
    }
    s.pos = (float4)(x, offset_m);
    s.normal = (float4)(normalize(c), as_float(h.prim));
    return s;
}

#endif /* FEN_SURFACE_HIT_H */
