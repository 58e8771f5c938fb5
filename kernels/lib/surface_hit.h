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

static inline SurfaceHit closest_surface(global const BvhNode* nodes, global const TriPacket4* packets,
                                         float3 org, float3 dir)
{
    const RayPre r = ray_setup(org, dir, 0.0f, INFINITY, FEN_BVH_WIDTH);
    uint packet_lane;
    const Hit h = bvh_intersect_closest_at(nodes, packets, &r, &packet_lane);
    SurfaceHit s;
    if (h.prim == FEN_INVALID_ID) {
        s.pos = (float4)(0.0f);
        s.normal = (float4)(0.0f, 0.0f, 0.0f, as_float(FEN_INVALID_ID));
    } else {
        const global TriPacket4* p = packets + (packet_lane >> 2);
        const uint lane = packet_lane & 3u;
        const float3 p0 = packet_vertex(p, lane, 0), p1 = packet_vertex(p, lane, 1),
                     p2 = packet_vertex(p, lane, 2);
        float offset_m;
        const float3 x = surface_point(p0, p1, p2, h.u, h.v, &offset_m);
        s.pos = (float4)(x, offset_m);
        s.normal = (float4)(normalize(cross(p1 - p0, p2 - p0)), as_float(h.prim));
    }
    return s;
}

#endif /* FEN_SURFACE_HIT_H */
