/* intersect.cl — wavefront stage 2: the next surface along every live path's ray.
 *
 * Work-item i: if paths[i] is alive, hits[i] = closest hit of its ray (t in (0, inf)); dead slots
 * are skipped (their hit is not read). Build with -DFEN_BVH_WIDTH=2|4|8. No atomics.
 */
#include "lib/bvh_traverse.h"
#include "shared/fen_render.h"

kernel void intersect_paths(global const PathState* paths, global Hit* hits, uint pool,
                            global const BvhNode* nodes, global const TriPacket4* packets)
{
    const uint i = get_global_id(0);
    if (i >= pool || !(paths[i].flags & FEN_PATH_ALIVE))
        return;
    const RayPre r = ray_setup(paths[i].org.xyz, paths[i].dir.xyz, 0.0f, INFINITY, FEN_BVH_WIDTH);
    hits[i] = bvh_intersect_closest(nodes, packets, &r);
}
