/* intersect.cl — wavefront stage 2: the next surface along every live path's ray
 * (lib/surface_hit.h).
 *
 * Work-item i: if paths[i] is alive, hits[i] = the closest surface along its ray (t in (0, inf)),
 * or a miss. Dead slots are skipped. Build with -DFEN_BVH_WIDTH=2|4|8. No atomics.
 */
#include "lib/surface_hit.h"
#include "shared/fen_render.h"

kernel void intersect_paths(global const PathState* paths, global SurfaceHit* hits, uint pool,
                            global const BvhNode* nodes, global const TriPacket4* packets)
{
    const uint i = get_global_id(0);
    if (i >= pool || !(paths[i].flags & FEN_PATH_ALIVE))
        return;
    hits[i] = closest_surface(nodes, packets, paths[i].org.xyz, paths[i].dir.xyz);
}
