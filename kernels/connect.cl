/* connect.cl — wavefront stage 4: trace each connection to the camera and splat what arrives.
 *
 * Work-item i: if connections[i] names a pixel, the segment from its origin to the pinhole is
 * traced (glass multiplies by T (1 - R), anything opaque blocks: lib/transmittance.h) and the
 * surviving contribution is added to the pixel in 128-bit fixed point (lib/accumulate.h). Built
 * with -DFEN_EMISSION_STATS (a strategy that gathers statistics), its luminance and squared
 * luminance also go to the emission cell part in connections[i].value.w (cell_stats; otherwise a
 * placeholder never read); a part flagged FEN_PART_ESTIMATE_ONLY feeds the statistics only.
 * Atomics: pixel accumulators, cell statistics, shadow-ray counter (per work-group).
 */
#include "lib/accumulate.h"
#include "lib/bvh_traverse.h"
#include "lib/group_count.h"
#include "lib/transmittance.h"

/* Traces connection i; returns 1 if there was one. */
static inline uint connect_one(uint i, global const RenderParams* params,
                               global const Connection* connections, global const BvhNode* nodes,
                               global const TriPacket4* packets, global const uint* prim_material,
                               global const DevMaterial* materials, volatile global ulong* accum,
                               volatile global ulong* cell_stats, volatile global ulong* counters)
{
    if (i >= params->pool_size)
        return 0;
    const Connection c = connections[i];
    const uint pixel = as_uint(c.org.w);
    if (pixel == FEN_INVALID_ID)
        return 0;
    const RayPre r = ray_setup(c.org.xyz, c.to_cam.xyz, 0.0f, 1.0f, FEN_BVH_WIDTH);
    const float3 trans = segment_transmittance(nodes, packets, prim_material, materials, &r,
                                               normalize(c.to_cam.xyz));
    if (trans.x > 0.0f || trans.y > 0.0f || trans.z > 0.0f) {
        const float3 value = c.value.xyz * trans;
#ifdef FEN_EMISSION_STATS
        const uint part = as_uint(c.value.w);
        if (!(part & FEN_PART_ESTIMATE_ONLY))
            splat_rgb(accum, pixel, value, params->fixed_scale, counters);
        cell_stats_add(cell_stats, part & ~FEN_PART_ESTIMATE_ONLY, value, params->fixed_scale,
                       params->stats_scale, counters);
#else
        splat_rgb(accum, pixel, value, params->fixed_scale, counters);
#endif
    }
    return 1;
}

kernel void connect_paths(global const RenderParams* params, global const Connection* connections,
                          global const BvhNode* nodes, global const TriPacket4* packets,
                          global const uint* prim_material, global const DevMaterial* materials,
                          volatile global ulong* accum, volatile global ulong* cell_stats,
                          volatile global ulong* counters)
{
    local uint traced_in_group;
    const uint traced = connect_one(get_global_id(0), params, connections, nodes, packets,
                                    prim_material, materials, accum, cell_stats, counters);
    group_count_add(counters + FEN_CTR_SHADOW_RAYS, traced, &traced_in_group);
}
