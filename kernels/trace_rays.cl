/* trace_rays.cl — closest-hit and any-hit queries over a buffer of rays.
 *
 * Used by `fenestra bench` and by the kernel tests that compare the device with the CPU reference
 * (bvh/bvh_traverse_ref.cpp). Build with -DFEN_BVH_WIDTH=2|4|8 to match the tree's layout.
 * Work-item i reads rays[i] and writes hits[i] (or occluded[i]); no atomics.
 */
#include "lib/bvh_traverse.h"

kernel void intersect_closest(global const Ray* rays, global Hit* hits, uint n,
                              global const BvhNode* nodes, global const TriPacket4* packets)
{
    const uint i = get_global_id(0);
    if (i >= n)
        return;
    const RayPre r = ray_setup_stored(&rays[i], FEN_BVH_WIDTH);
    hits[i] = bvh_intersect_closest(nodes, packets, &r);
}

kernel void intersect_any(global const Ray* rays, global uint* occluded, uint n,
                          global const BvhNode* nodes, global const TriPacket4* packets)
{
    const uint i = get_global_id(0);
    if (i >= n)
        return;
    const RayPre r = ray_setup_stored(&rays[i], FEN_BVH_WIDTH);
    occluded[i] = (uint)bvh_intersect_any(nodes, packets, &r);
}
