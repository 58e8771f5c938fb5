/* sensor.h — a path segment's flux added to the sensor cells it crosses (DESIGN.md §8).
 *
 * A light tracer's paths are samples of the light's flux: a segment of weight beta (lm per path)
 * that crosses a surface element of area A adds Y(beta) / A to that element's illuminance estimate
 * (lux x paths; the host divides by the paths). Sensors block nothing: the segment goes on. A cell
 * counts light arriving at the side its plane's normal faces (the segment travels against the
 * normal), as an illuminance meter lying there would.
 * Called for every segment of every path, from org towards dir (unit) up to t_max (the next
 * surface, INFINITY for a miss), by the wavefront's shade.cl and by the fused kernel, so a cell's
 * sum does not depend on the kernel form (integer sums: lib/accumulate.h). Segments of the portal
 * complement's estimate-only paths (FEN_PART_ESTIMATE_ONLY) add nothing, as they add nothing to
 * pixels. Cost: one plane test per sensor plane and segment; a crossing looks in one bucket.
 * Overflows of the 128-bit range are counted (FEN_CTR_OVERFLOWS) and must stay zero.
 * With daylight coefficients (info->patches > 0: shared/fen_sensor.h), a crossing also goes to its
 * cell's entry for the sky patch its path started from (the path's flags: lib/sky_patch.h), and,
 * if it came straight from the sky through nothing but glass (no diffuse surface has scattered it,
 * FEN_PATH_BRANCHED, and no glass has reflected it, FEN_PATH_REFLECTED), to the direct-light
 * matrix -- what annual sunlight exposure counts, and what the direct-sun pass (direct_sun.cl)
 * computes exactly for the sun.
 * Built with -DFEN_SENSOR_STATS (a learning strategy in a render with no image), each crossing's
 * illuminance over pi -- a luminance, the unit the pixels' statistics are kept in -- also goes to
 * the emission cell the path started in (lib/accumulate.h cell_stats_add), so that the strategy
 * learns where the light the sensors see comes from: by default the absolute target, the sum of
 * the cells' variances, which is what a grid's RMS error measures; with the strategy's relative
 * target each cell's share is scaled by its steer factor (about the grid's mean over the cell's
 * own illuminance: render/renderer.cpp), so that a dim room counts as much as a bright one. With
 * daylight coefficients each crossing's share is also weighted by its patch's luminance in the sky
 * the coefficients are for (an annual study: the year's mean sky), so that the strategy learns where
 * that sky's light comes from though the run renders a sky of 1 cd/m^2.
 */
#ifndef FEN_SENSOR_LIB_H
#define FEN_SENSOR_LIB_H

#include "lib/accumulate.h"
#include "lib/sampling.h"
#include "shared/fen_render.h"
#include "shared/fen_sensor.h"

typedef struct {
    global const DevSensorInfo* info;
    global const DevSensorPlane* planes;
    global const DevSensorCell* cells;
    global const uint* bucket_start;
    global const uint* bucket_cells;
    volatile global ulong* accum;  /* 2 words per cell */
    volatile global ulong* cell_stats;  /* the strategy's statistics (FEN_SENSOR_STATS only) */
    global const float* steer;          /* per cell: the factor on what it adds to them (1: absolute);
                                           then, with daylight coefficients, per sky patch */
    float stats_fixed_scale, stats_scale;
} Sensors;

static inline void sensor_record(const Sensors* s, float3 org, float3 dir, float t_max, float4 beta,
                                 uint path_flags, volatile global ulong* counters)
{
    const uint planes = s->info->planes;
    if (planes == 0u || (as_uint(beta.w) & FEN_PART_ESTIMATE_ONLY))
        return;
    const float flux = rgb_luminance(beta.xyz);
    if (!(flux > 0.0f))
        return;
    const float scale = s->info->fixed_scale;
    const uint cells = s->info->cells, patches = s->info->patches;
    const uint patch = (path_flags >> FEN_PATH_PATCH_SHIFT) & FEN_PATH_PATCH_MASK;
    const int tagged = patches && patch < patches; /* always, when the emitter tagged for these sums */
    const int direct = !(path_flags & (FEN_PATH_BRANCHED | FEN_PATH_REFLECTED));
    for (uint k = 0; k < planes; ++k) {
        const global DevSensorPlane* pl = s->planes + k;
        const float3 n = pl->normal.xyz;
        const float cos_n = dot(dir, n);
        if (!(cos_n < 0.0f))
            continue; /* parallel, or arriving at the back */
        const float t = (pl->origin.w - dot(org, n)) / cos_n;
        if (!(t > 0.0f && t < t_max))
            continue;
        const float3 x = org + t * dir - pl->origin.xyz;
        const float u = dot(x, pl->u_axis.xyz), v = dot(x, pl->v_axis.xyz);
        const float fu = u * pl->normal.w, fv = v * pl->normal.w;
        if (!(fu >= 0.0f && fv >= 0.0f && fu < (float)pl->cols && fv < (float)pl->rows))
            continue;
        const uint b = pl->bucket_first + min((uint)fv, pl->rows - 1u) * pl->cols + min((uint)fu, pl->cols - 1u);
        const uint end = s->bucket_start[b + 1];
        for (uint i = s->bucket_start[b]; i < end; ++i) {
            const uint c = s->bucket_cells[i];
            const DevSensorCell cell = s->cells[c];
            /* half-open squares: a point on a shared edge belongs to one cell */
            const float du = u - cell.u, dv = v - cell.v;
            if (du >= -cell.half_side && du < cell.half_side && dv >= -cell.half_side && dv < cell.half_side) {
                const float e = flux * cell.inv_area * scale;
                if (!fixed_add128(s->accum + 2 * (ulong)c, e))
                    counter_add(counters, FEN_CTR_OVERFLOWS, 1);
                if (tagged) {
                    /* the daylight coefficients: by the sky patch the path left (patch < patches:
                       lib/sky_patch.h), and again while no diffuse surface has scattered it */
                    const ulong row = (ulong)cells + (ulong)c * patches + patch;
                    if (!fixed_add128(s->accum + 2 * row, e))
                        counter_add(counters, FEN_CTR_OVERFLOWS, 1);
                    if (direct && !fixed_add128(s->accum + 2 * (row + (ulong)cells * patches), e))
                        counter_add(counters, FEN_CTR_OVERFLOWS, 1);
                }
#ifdef FEN_SENSOR_STATS
                /* with daylight coefficients, times the patch's weight (steer[cells + patch]): the
                   statistics of the sky the learning is for, not of the unit sky rendered */
                const float l = flux * cell.inv_area * (1.0f / FEN_PI) * s->steer[c] *
                                (tagged ? s->steer[cells + patch] : 1.0f);
                cell_stats_add(s->cell_stats, as_uint(beta.w) & ~FEN_PART_ESTIMATE_ONLY, (float3)(l),
                               s->stats_fixed_scale, s->stats_scale, counters);
#endif
            }
        }
    }
}

#endif /* FEN_SENSOR_LIB_H */
