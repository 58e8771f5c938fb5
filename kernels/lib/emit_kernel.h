/* emit_kernel.h — the one emission wrapper (wavefront stage 1): give every dead slot of the path
 * pool a new light path, drawn by the strategy the including file names (DESIGN.md §3). Each
 * kernels/emit_<strategy>.cl includes its strategy's header first, defines FEN_EMITTER_TYPE,
 * _ARGS, _MAKE, _EMIT and _REJECTS (lib/emit_*.h provide them), then includes this.
 *
 * Work-item i owns slot i. A dead slot takes the next path index from counters[FEN_CTR_NEXT_PATH]
 * (a ticket, one global atomic per work-group: lib/group_count.h); indices at or past
 * params->path_end leave it dead (the batch is drained). A candidate the strategy rejects spends
 * its index and leaves the slot dead for this iteration; FEN_CTR_EMITTED counts the paths that
 * started. Which slot gets which index varies with scheduling; the path does not (its random
 * numbers are keyed by its index), nor does the image (fixed-point sums).
 * FEN_EMITTER_REJECTS: whether the strategy may reject a candidate (then the count of started
 * paths waits for it) or always emits (then the count comes first and the emission runs after the
 * work-group's last barrier: on PoCL nothing of it is kept across a barrier).
 * Why one file per strategy rather than one file with #if: which headers come first decides how
 * the code after them is compiled (lib/tri_packet.h turns floating-point contraction off for the
 * rest of the program), and a strategy's images must not change because another strategy's
 * header was compiled too.
 */
#ifndef FEN_EMIT_KERNEL_H
#define FEN_EMIT_KERNEL_H

#include "lib/group_count.h"
#include "lib/sky_patch.h"

kernel void emit_paths(global const RenderParams* params, volatile global ulong* counters,
                       global PathState* paths, FEN_EMITTER_ARGS)
{
    local uint group_count;
    local ulong group_base;
    const uint i = get_global_id(0);
    const int dead = i < params->pool_size && !(paths[i].flags & FEN_PATH_ALIVE);
    const ulong path = group_ticket(counters + FEN_CTR_NEXT_PATH, dead, &group_count, &group_base);
    const int ticket = dead && path < params->path_end;
#if FEN_EMITTER_REJECTS
    int emitted = 0;
    if (ticket) {
        const FEN_EMITTER_TYPE emitter = FEN_EMITTER_MAKE;
        PathState p;
        emitted = FEN_EMITTER_EMIT(params, &emitter, path, &p);
        if (emitted) {
            path_tag_sky_patch(&p);
            paths[i] = p;
        }
    }
    group_count_add(counters + FEN_CTR_EMITTED, (uint)emitted, &group_count);
#else
    group_count_add(counters + FEN_CTR_EMITTED, (uint)ticket, &group_count);
    if (!ticket)
        return;
    const FEN_EMITTER_TYPE emitter = FEN_EMITTER_MAKE;
    PathState p;
    FEN_EMITTER_EMIT(params, &emitter, path, &p);
    path_tag_sky_patch(&p);
    paths[i] = p;
#endif
}

/* The fused kernel uses the same emitter (built with -DFEN_FUSED by the host: lib/fused_kernel.h). */
#ifdef FEN_FUSED
#include "lib/fused_kernel.h"
#endif

#endif /* FEN_EMIT_KERNEL_H */
