/* emit_portal.cl — wavefront stage 1 for the `portal` strategy: like emit.cl (one ticket per dead
 * slot, per work-group), with paths from lib/emit_portal.h. A rejected candidate spends its path
 * index and leaves the slot dead for this iteration.
 * Build with -DFEN_BVH_WIDTH (the portals' BVH has the scene's layout).
 */
#include "lib/bvh_traverse.h"
#include "lib/emit_portal.h"
#include "lib/group_count.h"

kernel void emit_portal_paths(global const RenderParams* params, volatile global ulong* counters,
                              global PathState* paths, global const float* sky_theta,
                              global const float* sky_phi, global const float* sky_values,
                              global const float* sky_factor, global const uint* source_alias, global const float4* portal_groups,
                              global const uint* portal_range, global const ulong* portal_cdf,
                              global const float4* portal_vertices,
                              global const BvhNode* portal_nodes,
                              global const TriPacket4* portal_packets)
{
    local uint group_count;
    local ulong group_base;
    const uint i = get_global_id(0);
    const int dead = i < params->pool_size && !(paths[i].flags & FEN_PATH_ALIVE);
    const ulong path = group_ticket(counters + FEN_CTR_NEXT_PATH, dead, &group_count, &group_base);
    int emitted = 0;
    if (dead && path < params->path_end) {
        const Sky sky = sky_from(sky_theta, sky_phi, sky_values, sky_factor,
                                 params->sky_theta_nodes, params->sky_phi_nodes);
        const SourceTable sources = source_table(source_alias, params->source_alias_shift);
        const Portals portals =
            portals_from(portal_groups, portal_range, portal_cdf, portal_vertices, portal_nodes,
                         portal_packets, params->portal_groups);
        PathState p;
        emitted = emit_portal(params, &sky, &sources, &portals, path, &p);
        if (emitted)
            paths[i] = p;
    }
    group_count_add(counters + FEN_CTR_EMITTED, (uint)emitted, &group_count);
}
