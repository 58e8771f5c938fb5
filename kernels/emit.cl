/* emit.cl — wavefront stage 1: give every dead slot of the path pool a new light path.
 *
 * Work-item i owns slot i. A dead slot takes the next path index from counters[FEN_CTR_NEXT_PATH]
 * (atomic ticket); indices at or past params->path_end leave it dead (the batch is drained).
 * Which slot gets which index varies with scheduling; the path does not (its random numbers are
 * keyed by its index), nor does the image (fixed-point sums).
 * Reads: params, sky tables. Writes: paths[i]. Atomics: the ticket.
 */
#include "lib/accumulate.h"
#include "lib/emit_uniform.h"

kernel void emit_paths(global const RenderParams* params, volatile global ulong* counters,
                       global PathState* paths, global const float* sky_theta,
                       global const float* sky_phi, global const float* sky_values,
                       global const ulong* sky_cdf, global const float* sky_factor)
{
    const uint i = get_global_id(0);
    if (i >= params->pool_size || (paths[i].flags & FEN_PATH_ALIVE))
        return;
    const ulong path = atom_inc(counters + FEN_CTR_NEXT_PATH);
    if (path >= params->path_end)
        return;
    Sky sky;
    sky.theta = sky_theta;
    sky.phi = sky_phi;
    sky.values = sky_values;
    sky.cdf = sky_cdf;
    sky.factor = sky_factor;
    sky.nt = params->sky_theta_nodes;
    sky.np = params->sky_phi_nodes;
    paths[i] = emit_uniform(params, &sky, path);
}
