/* connect.cl — wavefront stage 4: trace each connection to the camera and splat what arrives
 * (lib/connect_path.h).
 *
 * Work-item i: if connections[i] names a pixel, connect_path() traces and splats it.
 * Arguments follow connect_path(); stats_pixel_scale is read only with FEN_STATS_PIXEL_SCALE,
 * guide_stats only for connections with a first-bounce guide record, window_stats only for those
 * made with weight windows on, opening_stats only for those of paths that entered by a learned
 * opening (lib/opening_aim.h).
 * Atomics: pixel accumulators, cell statistics, shadow-ray counter (per work-group).
 */
#include "lib/connect_path.h"
#include "lib/group_count.h"

/* Traces connection i; returns 1 if there was one. */
static inline uint connect_one(uint i, global const RenderParams* params,
                               global const Connection* connections, global const BvhNode* nodes,
                               global const TriPacket4* packets, global const uint* prim_material,
                               global const DevMaterial* materials, volatile global ulong* accum,
                               volatile global ulong* cell_stats, global const float* stats_pixel_scale,
                               volatile global ulong* guide_stats, volatile global ulong* window_stats,
                               volatile global ulong* opening_stats, volatile global ulong* counters)
{
    if (i >= params->pool_size)
        return 0;
    const Connection c = connections[i];
    if (as_uint(c.org.w) == FEN_INVALID_ID)
        return 0;
    connect_path(params, &c, nodes, packets, prim_material, materials, accum, cell_stats, stats_pixel_scale,
                 guide_stats, window_stats, opening_stats, counters);
    return 1;
}

kernel void connect_paths(global const RenderParams* params, global const Connection* connections,
                          global const BvhNode* nodes, global const TriPacket4* packets,
                          global const uint* prim_material, global const DevMaterial* materials,
                          volatile global ulong* accum, volatile global ulong* cell_stats,
                          global const float* stats_pixel_scale, volatile global ulong* guide_stats,
                          volatile global ulong* window_stats, volatile global ulong* opening_stats,
                          volatile global ulong* counters)
{
    local uint traced_in_group;
    const uint traced = connect_one(get_global_id(0), params, connections, nodes, packets,
                                    prim_material, materials, accum, cell_stats, stats_pixel_scale,
                                    guide_stats, window_stats, opening_stats, counters);
    group_count_add(counters + FEN_CTR_SHADOW_RAYS, traced, &traced_in_group);
}
