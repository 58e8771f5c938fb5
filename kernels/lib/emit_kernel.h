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
 * FEN_EMITTER_OPENINGS (1 for adaptive), built with -DFEN_OPENING_WALKS=1 (the host, when
 * --adaptive-openings-share > 0): a share RenderParams.openings_share of the indices start on the
 * opening aim's panes instead (lib/opening_walk.h), for which every strategy's kernel takes the
 * scene's buffers (nodes to opening_aim) after `paths`; FEN_CTR_OPENING_WALKS and
 * FEN_CTR_OPENING_WALK_RAYS count them. Without the define the walk's code (a BVH traversal) is not
 * compiled into the emission kernel at all.
 * Why one file per strategy rather than one file with #if: which headers come first decides how
 * the code after them is compiled (lib/tri_packet.h turns floating-point contraction off for the
 * rest of the program), and a strategy's images must not change because another strategy's
 * header was compiled too.
 */
#ifndef FEN_EMIT_KERNEL_H
#define FEN_EMIT_KERNEL_H

#include "lib/group_count.h"
#include "lib/opening_walk.h"
#include "lib/sky_patch.h"

#ifndef FEN_EMITTER_OPENINGS
#define FEN_EMITTER_OPENINGS 0
#endif
#if FEN_EMITTER_OPENINGS && defined(FEN_OPENING_WALKS)
#define FEN_WALKS 1
#else
#define FEN_WALKS 0
#endif

/* Starts path `path` in *p: on an opening's pane (lib/opening_walk.h; *walks, *walk_rays count them)
   or by the strategy, whose paths then weigh 1 / (1 - share). Returns 0 when none starts (a rejected
   candidate, a walk that found no light). */
static inline int start_path(global const RenderParams* params, const FEN_EMITTER_TYPE* emitter,
                             const OpeningScene* os, ulong path, PathState* p, ulong* walks, ulong* walk_rays)
{
#if FEN_WALKS
    RngBlock pick;
    if (opening_walk_picked(params, os->aim, path, &pick)) {
        *walks += 1;
        const uint part = emitter->params->walk_part + (uint)(path & (FEN_WALK_PARTS - 1u));
        return opening_walk(params, &emitter->sky, emitter->params->sun_weight.xyz, part, os, path, pick, p,
                            walk_rays);
    }
#else
    (void)os;
    (void)walks;
    (void)walk_rays;
#endif
#if FEN_EMITTER_REJECTS
    if (!FEN_EMITTER_EMIT(params, emitter, path, p))
        return 0;
#else
    FEN_EMITTER_EMIT(params, emitter, path, p);
#endif
#if FEN_WALKS
    if (opening_walks_on(params, os->aim))
        p->beta.xyz *= 1.0f / (1.0f - params->openings_share);
#endif
    return 1;
}

kernel void emit_paths(global const RenderParams* params, volatile global ulong* counters,
                       global PathState* paths, global const BvhNode* nodes, global const TriPacket4* packets,
                       global const uint* prim_material, global const DevMaterial* materials,
                       global const float4* prim_uv, global const uint* texels,
                       global const OpeningAim* opening_aim, FEN_EMITTER_ARGS)
{
    local uint group_count;
    local ulong group_base;
    const uint i = get_global_id(0);
    const int dead = i < params->pool_size && !(paths[i].flags & FEN_PATH_ALIVE);
    const ulong path = group_ticket(counters + FEN_CTR_NEXT_PATH, dead, &group_count, &group_base);
    const int ticket = dead && path < params->path_end;
#if FEN_EMITTER_REJECTS
    int emitted = 0;
    ulong walks = 0, walk_rays = 0;
    if (ticket) {
        const FEN_EMITTER_TYPE emitter = FEN_EMITTER_MAKE;
        const OpeningScene os = {nodes, packets, {prim_material, materials, prim_uv, texels}, opening_aim};
        PathState p;
        emitted = start_path(params, &emitter, &os, path, &p, &walks, &walk_rays);
        if (emitted) {
            path_tag_sky_patch(&p);
            paths[i] = p;
        }
    }
    group_count_add(counters + FEN_CTR_EMITTED, (uint)emitted, &group_count);
#if FEN_WALKS
    group_count_add(counters + FEN_CTR_OPENING_WALKS, (uint)walks, &group_count);
    group_count_add(counters + FEN_CTR_OPENING_WALK_RAYS, (uint)walk_rays, &group_count);
#endif
#else
    (void)nodes;
    (void)packets;
    (void)prim_material;
    (void)materials;
    (void)prim_uv;
    (void)texels;
    (void)opening_aim;
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
