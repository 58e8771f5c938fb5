/* intersect.cl — wavefront stage 2: the next surface along every live path's ray.
 *
 * Work-item i: if paths[i] is alive, hits[i] = the closest surface along its ray (t in (0, inf)):
 * point, offset for a ray leaving it, unit geometric normal and primitive -- computed here from
 * the triangle packet traversal has just tested, still in cache; shade.cl would otherwise fetch
 * the triangle again (measured: 43 % of its time on that miss). Dead slots are skipped.
 * Build with -DFEN_BVH_WIDTH=2|4|8. No atomics.
 */
#include "lib/bvh_traverse.h"
#include "lib/ray_offset.h"
#include "lib/scene_access.h"
#include "shared/fen_render.h"

kernel void intersect_paths(global const PathState* paths, global SurfaceHit* hits, uint pool,
                            global const BvhNode* nodes, global const TriPacket4* packets)
{
    const uint i = get_global_id(0);
    if (i >= pool || !(paths[i].flags & FEN_PATH_ALIVE))
        return;
    const RayPre r = ray_setup(paths[i].org.xyz, paths[i].dir.xyz, 0.0f, INFINITY, FEN_BVH_WIDTH);
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
    hits[i] = s;
}
