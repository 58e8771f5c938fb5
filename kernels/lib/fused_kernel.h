/* fused_kernel.h — the whole light path in one kernel, for CPU devices (README "Kernels"): each
 * work-item takes path indices FEN_FUSED_CHUNK at a time from counters[FEN_CTR_NEXT_PATH] (so
 * the work balances whatever the paths' lengths) and runs each path to its end -- emit,
 * intersect, shade, connect, and the branches of a split path -- with the path in registers, where the wavefront writes it to
 * memory four times a bounce and launches four kernels an iteration.
 *
 * It is built from the strategy's emission file with -DFEN_FUSED (lib/emit_kernel.h includes it
 * there, after FEN_EMITTER_* are defined) and calls the functions the wavefront stages call:
 * the emitter, closest_surface() (lib/surface_hit.h), shade_path() (lib/shade_path.h) and
 * connect_path() (lib/connect_path.h). A path's random numbers are keyed by its index and
 * depth, and every program is compiled without contraction (cl/kernel_source.cpp), so a path
 * computes the same numbers here as there; pixels and statistics are integer sums. Hence the
 * image is bit-identical to the wavefront's (tests/render/fused_test.cpp).
 * Built with -DFEN_HAS_SENSORS, every segment adds its flux to the sensor cells it crosses
 * (lib/sensor.h), as shade.cl does in the wavefront.
 * Paths start as the wavefront's do (lib/emit_kernel.h start_path, the openings' walks too).
 * Counters: emitted paths, extension and shadow rays, diffuse and guided vertices, the walks, added once per
 * work-item at its end. The weight windows' arrivals are held in registers (lib/guide.h
 * HeldArrivals) and added when their entry is needed and at the end: integer sums, the same bytes
 * as the wavefront's adding each at once.
 */
#ifndef FEN_FUSED_KERNEL_H
#define FEN_FUSED_KERNEL_H

#include "lib/connect_path.h"
#include "lib/sensor.h"
#include "lib/shade_path.h"
#include "lib/surface_hit.h"

#define FEN_FUSED_CHUNK 8

kernel void trace_fused(global const RenderParams* params, volatile global ulong* counters,
                        global const BvhNode* nodes, global const TriPacket4* packets,
                        global const uint* prim_material, global const DevMaterial* materials,
                        global const float4* prim_uv, global const uint* texels,
                        global const DevCamera* cam, volatile global ulong* accum,
                        volatile global ulong* cell_stats, global const float* stats_pixel_scale,
                        global const GuideParams* guide_params, global const uint* guide_tables,
                        volatile global ulong* guide_stats, volatile global ulong* guide_window_stats,
                        global const OpeningAim* opening_aim, global const uint2* opening_prims,
                        volatile global ulong* opening_stats,
                        global const DevSensorInfo* sensor_info, global const DevSensorPlane* sensor_planes,
                        global const DevSensorCell* sensor_cells, global const uint* sensor_bucket_start,
                        global const uint* sensor_bucket_cells, volatile global ulong* sensor_accum,
                        global const float* sensor_steer, FEN_EMITTER_ARGS)
{
    /* the sensors' statistics go to the strategy's own (FEN_SENSOR_STATS) */
    const Sensors sensors = {sensor_info, sensor_planes, sensor_cells, sensor_bucket_start, sensor_bucket_cells,
                             sensor_accum, cell_stats, sensor_steer, params->fixed_scale, params->stats_scale};
    const FEN_EMITTER_TYPE emitter = FEN_EMITTER_MAKE;
    HeldArrivals held;
    held_arrivals_init(&held);
    const Guide guide = {guide_params, guide_tables, guide_window_stats, &held, opening_aim, opening_prims, opening_stats};
    const SurfaceMaterials sm = {prim_material, materials, prim_uv, texels};
    const OpeningScene os = {nodes, packets, sm, opening_aim};
    ulong emitted = 0, extension = 0, shadow = 0, walks = 0, walk_rays = 0;
    VertexTally tally = {0, 0, 0, 0};
    for (;;) {
        const ulong first = atom_add(counters + FEN_CTR_NEXT_PATH, (ulong)FEN_FUSED_CHUNK);
        if (first >= params->path_end)
            break;
        const ulong last = min(first + (ulong)FEN_FUSED_CHUNK, params->path_end);
        for (ulong path = first; path < last; ++path) {
            PathState p;
            if (!start_path(params, &emitter, &os, path, &p, &walks, &walk_rays))
                continue;
            path_tag_sky_patch(&p);
            ++emitted;
            SplitState split; /* read only under FEN_PATH_SPLIT, which shade_path() sets with it */
            for (;;) {
                ++extension;
                const SurfaceHit h = closest_surface(nodes, packets, p.org.xyz, p.dir.xyz);
#ifdef FEN_HAS_SENSORS
                sensor_record(&sensors, p.org.xyz, p.dir.xyz,
                              as_uint(h.normal.w) != FEN_INVALID_ID ? distance(h.pos.xyz, p.org.xyz) : INFINITY,
                              p.beta, p.flags, counters);
#endif
                if (as_uint(h.normal.w) == FEN_INVALID_ID) {
                    if (next_branch(params, &guide, &p, &split, &sm, cam, &tally, counters))
                        continue;
                    break;
                }
                Connection c;
                const int alive = shade_path(params, &guide, &p, &h, &sm, cam, &c, &split, &tally, counters);
                if (as_uint(c.org.w) != FEN_INVALID_ID) {
                    connect_path(params, &c, nodes, packets, prim_material, materials, accum, cell_stats,
                                 stats_pixel_scale, guide_stats, guide_window_stats, opening_stats, counters);
                    ++shadow;
                }
                if (!alive && !next_branch(params, &guide, &p, &split, &sm, cam, &tally, counters))
                    break;
            }
        }
    }
    guide_arrivals_flush(&guide);
    if (emitted)
        atom_add(counters + FEN_CTR_EMITTED, emitted);
    if (extension)
        atom_add(counters + FEN_CTR_EXTENSION_RAYS, extension);
    if (shadow)
        atom_add(counters + FEN_CTR_SHADOW_RAYS, shadow);
    if (tally.diffuse)
        atom_add(counters + FEN_CTR_DIFFUSE_VERTICES, tally.diffuse);
    if (tally.guided)
        atom_add(counters + FEN_CTR_GUIDED_VERTICES, tally.guided);
    if (tally.split)
        atom_add(counters + FEN_CTR_SPLIT_BRANCHES, tally.split);
    if (tally.culled)
        atom_add(counters + FEN_CTR_WINDOW_CULLS, tally.culled);
    if (walks)
        atom_add(counters + FEN_CTR_OPENING_WALKS, walks);
    if (walk_rays)
        atom_add(counters + FEN_CTR_OPENING_WALK_RAYS, walk_rays);
}

#endif /* FEN_FUSED_KERNEL_H */
