/* shade.cl — wavefront stage 3: what happens at each live path's hit (lib/shade_path.h).
 *
 * Work-item i, slot i: a miss ends the path (or its branch); a surface is shaded by shade_path(),
 * which may write a camera connection for connect.cl. Writes paths[i], splits[i] while branches of
 * a split wait, and connections[i] (pixel FEN_INVALID_ID when there is none). Atomics: the alive
 * and vertex counters (per work-group), the max-depth counter, and with weight windows the guide's
 * arrival statistics (lib/guide.h guide_arrive). The guide's tables (lib/guide.h) are read at
 * first diffuse vertices when guide_params->slots > 0. Built with -DFEN_HAS_SENSORS, the segment
 * that led to the hit (or to the miss) first adds its flux to the sensor cells it crosses
 * (lib/sensor.h); without it the sensor arguments are never read.
 */
#include "lib/group_count.h"
#include "lib/sensor.h"
#include "lib/shade_path.h"

/* Shades slot i; returns 1 if its path goes on. A branch of a split path that ends hands its slot
   to the next branch (lib/shade_path.h next_branch). */
static inline uint shade_one(uint i, global const RenderParams* params, const Guide* guide,
                             global PathState* paths,
                             global SplitState* splits, global const SurfaceHit* hits,
                             const SurfaceMaterials* sm,
                             global const DevCamera* cam, global Connection* connections,
                             const Sensors* sensors, VertexTally* t, volatile global ulong* counters)
{
    if (i >= params->pool_size)
        return 0;
    connections[i].org.w = as_float(FEN_INVALID_ID);
    PathState p = paths[i];
    if (!(p.flags & FEN_PATH_ALIVE))
        return 0;
    SplitState s;
    if (p.flags & FEN_PATH_SPLIT)
        s = splits[i];
    const SurfaceHit h = hits[i];
#ifdef FEN_HAS_SENSORS
    const float t_max = as_uint(h.normal.w) != FEN_INVALID_ID ? distance(h.pos.xyz, p.org.xyz) : INFINITY;
    sensor_record(sensors, p.org.xyz, p.dir.xyz, t_max, p.beta, p.flags, counters);
#else
    (void)sensors;
#endif
    int alive = 0;
    if (as_uint(h.normal.w) != FEN_INVALID_ID) {
        Connection c;
        alive = shade_path(params, guide, &p, &h, sm, cam, &c, &s, t, counters);
        if (as_uint(c.org.w) != FEN_INVALID_ID)
            connections[i] = c;
    }
    if (!alive)
        alive = next_branch(params, guide, &p, &s, sm, cam, t, counters);
    if (!alive) {
        paths[i].flags = 0;
        return 0;
    }
    if (p.flags & FEN_PATH_SPLIT)
        splits[i] = s;
    paths[i] = p;
    return 1;
}

kernel void shade_paths(global const RenderParams* params, global PathState* paths,
                        global SplitState* splits, global const SurfaceHit* hits,
                        global const uint* prim_material, global const DevMaterial* materials,
                        global const float4* prim_uv, global const uint* texels, global const DevCamera* cam,
                        global Connection* connections, global const GuideParams* guide_params,
                        global const uint* guide_tables, volatile global ulong* guide_window_stats,
                        global const OpeningAim* opening_aim, global const uint2* opening_prims,
                        volatile global ulong* opening_stats, global const DevSensorInfo* sensor_info, global const DevSensorPlane* sensor_planes,
                        global const DevSensorCell* sensor_cells, global const uint* sensor_bucket_start,
                        global const uint* sensor_bucket_cells, volatile global ulong* sensor_accum,
                        volatile global ulong* sensor_cell_stats, global const float* sensor_steer,
                        volatile global ulong* counters)
{
    local uint alive_in_group;
    VertexTally tally = {0, 0, 0, 0};
    /* one path a work-item: nothing to hold (lib/guide.h HeldArrivals) */
    const Guide guide = {guide_params, guide_tables, guide_window_stats, 0, opening_aim, opening_prims, opening_stats};
    const SurfaceMaterials sm = {prim_material, materials, prim_uv, texels};
    const Sensors sensors = {sensor_info, sensor_planes, sensor_cells, sensor_bucket_start, sensor_bucket_cells,
                             sensor_accum, sensor_cell_stats, sensor_steer, params->fixed_scale, params->stats_scale};
    const uint alive = shade_one(get_global_id(0), params, &guide, paths, splits, hits, &sm, cam, connections,
                                 &sensors, &tally, counters);
    group_count_add(counters + FEN_CTR_ALIVE, alive, &alive_in_group);
    group_count_add(counters + FEN_CTR_DIFFUSE_VERTICES, (uint)tally.diffuse, &alive_in_group);
    group_count_add(counters + FEN_CTR_GUIDED_VERTICES, (uint)tally.guided, &alive_in_group);
    group_count_add(counters + FEN_CTR_SPLIT_BRANCHES, (uint)tally.split, &alive_in_group);
    group_count_add(counters + FEN_CTR_WINDOW_CULLS, (uint)tally.culled, &alive_in_group);
}
