/* emit.cl — wavefront stage 1: give every dead slot of the path pool a new light path.
 *
 * Work-item i owns slot i. A dead slot takes the next path index from counters[FEN_CTR_NEXT_PATH]
 * (a ticket, one global atomic per work-group: lib/group_count.h); indices at or past
 * params->path_end leave it dead (the batch is drained).
 * Which slot gets which index varies with scheduling; the path does not (its random numbers are
 * keyed by its index), nor does the image (fixed-point sums).
 * Reads: params, sky and source tables. Writes: paths[i]. Atomics: the ticket.
 */
#include "lib/emit_uniform.h"
#include "lib/group_count.h"

kernel void emit_paths(global const RenderParams* params, volatile global ulong* counters,
                       global PathState* paths, global const float* sky_theta,
                       global const float* sky_phi, global const float* sky_values,
                       global const float* sky_factor, global const uint* source_alias)
{
    local uint group_count;
    local ulong group_base;
    const uint i = get_global_id(0);
    const int dead = i < params->pool_size && !(paths[i].flags & FEN_PATH_ALIVE);
    const ulong path = group_ticket(counters + FEN_CTR_NEXT_PATH, dead, &group_count, &group_base);
    const int emit = dead && path < params->path_end;
    group_count_add(counters + FEN_CTR_EMITTED, (uint)emit, &group_count);
    if (!emit)
        return;
    const Sky sky = sky_from(sky_theta, sky_phi, sky_values, sky_factor, params->sky_theta_nodes,
                             params->sky_phi_nodes);
    const SourceTable sources = source_table(source_alias, params->source_alias_shift);
    paths[i] = emit_uniform(params, &sky, &sources, path);
}
