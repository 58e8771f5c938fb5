/* connect_path.h — a camera connection traced and splatted, for the wavefront's connect.cl and the
 * fused kernel (lib/fused_kernel.h) alike.
 *
 * The segment from the connection's origin to the pinhole is traced (glass multiplies by
 * T (1 - R), anything opaque blocks: lib/transmittance.h) and the surviving contribution is added
 * to the pixel in 128-bit fixed point (lib/accumulate.h). Built with -DFEN_EMISSION_STATS (a
 * strategy that gathers statistics), its luminance and squared luminance also go to the emission
 * cell part in c->value.w (cell_stats; otherwise a placeholder never read); a part flagged
 * FEN_PART_ESTIMATE_ONLY feeds the statistics only. With -DFEN_STATS_PIXEL_SCALE the statistics
 * see the contribution times its pixel's factor in stats_pixel_scale (the adaptive strategy's
 * relative target, DESIGN.md §3.3): steering only, never the image. A connection that carries a
 * first-bounce guide record (c->guide.x > 0) adds its luminance to that box's statistics in
 * guide_stats (lib/guide.h), whatever the strategy, and with weight windows (c->guide.z > 0) to the
 * window statistics of the first vertex's slot in window_stats (c->guide.z: their scale; c->guide.w:
 * the slot and the power). Requires lib/bvh_traverse.h
 * (FEN_BVH_WIDTH).
 */
#ifndef FEN_CONNECT_PATH_H
#define FEN_CONNECT_PATH_H

#include "lib/accumulate.h"
#include "lib/bvh_traverse.h"
#include "lib/guide.h"
#include "lib/opening_aim.h"
#include "lib/transmittance.h"

static inline void connect_path(global const RenderParams* params, const Connection* c,
                                global const BvhNode* nodes, global const TriPacket4* packets,
                                global const uint* prim_material, global const DevMaterial* materials,
                                volatile global ulong* accum, volatile global ulong* cell_stats,
                                global const float* stats_pixel_scale, volatile global ulong* guide_stats,
                                volatile global ulong* window_stats, volatile global ulong* opening_stats,
                                volatile global ulong* counters)
{
    const uint pixel = as_uint(c->org.w);
    const RayPre r = ray_setup(c->org.xyz, c->to_cam.xyz, 0.0f, 1.0f, FEN_BVH_WIDTH);
    const float3 trans = segment_transmittance(nodes, packets, prim_material, materials, &r,
                                               normalize(c->to_cam.xyz));
    if (trans.x > 0.0f || trans.y > 0.0f || trans.z > 0.0f) {
        const float3 value = c->value.xyz * trans;
        if (c->guide.x > 0.0f)
            guide_record(guide_stats, window_stats, c->guide.x, as_uint(c->guide.y), rgb_luminance(value),
                         c->guide.z, as_uint(c->guide.w), as_uint(c->to_cam.w), counters);
        opening_deliver(opening_stats, as_uint(c->to_cam.w), rgb_luminance(value),
                        params->fixed_scale * FEN_GUIDE_WINDOW_SCALE);
#ifdef FEN_EMISSION_STATS
        const uint part = as_uint(c->value.w);
        if (!(part & FEN_PART_ESTIMATE_ONLY))
            splat_rgb(accum, pixel, value, params->fixed_scale, counters);
#ifdef FEN_STATS_PIXEL_SCALE
        const float3 steer = value * stats_pixel_scale[pixel];
#else
        const float3 steer = value;
        (void)stats_pixel_scale;
#endif
        cell_stats_add(cell_stats, part & ~FEN_PART_ESTIMATE_ONLY, steer, params->fixed_scale,
                       params->stats_scale, counters);
#else
        (void)cell_stats;
        (void)stats_pixel_scale;
        splat_rgb(accum, pixel, value, params->fixed_scale, counters);
#endif
    }
}

#endif /* FEN_CONNECT_PATH_H */
