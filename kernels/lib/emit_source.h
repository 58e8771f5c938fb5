/* emit_source.h — what every emission strategy shares (DESIGN.md §3): starting a path, the
 * direction a source sends light in from two uniforms the caller hands over, the source table of
 * `uniform` and `portal` (the sun, or one sky cell, from 32 random bits with exact probabilities;
 * host: host/emission/uniform_emission.h), `uniform`'s lines into the scene's bounding box (also
 * the portal complement's), and moving an origin back outside the scene.
 */
#ifndef FEN_EMIT_SOURCE_H
#define FEN_EMIT_SOURCE_H

#include "lib/rng.h"
#include "lib/sky.h"
#include "shared/fen_emission.h"
#include "shared/fen_render.h"

typedef struct {
    const global SourceParams* params;
    const global uint* alias; /* entry 0 the sun, 1 + k sky cell k (lib/sampling.h alias_pick) */
} SourceTable;

/* A fresh path with index `path`; the strategy fills org, dir and beta. */
static inline void path_start(PathState* p, ulong path)
{
    p->path_lo = (uint)path;
    p->path_hi = (uint)(path >> 32);
    p->depth = 0;
    p->flags = FEN_PATH_ALIVE;
}

/* The 32 bits that pick path `path`'s entry of the strategy's first table (the source table, or
   adaptive's cells), an integer alias table of 2^(32 - shift) columns (lib/sampling.h alias_pick:
   the high bits choose the column, the low `shift` bits between it and its alias). With
   params->pick_step > 0 the column bits come from a lattice the host lays over each run of the
   wavefront (a batch, or a learning pass within one), c = pick_offset + path pick_step (mod 2^32)
   -- one sweep of [0, 2^32) per run at an offset drawn for it -- and the low bits stay the path's
   own random bits. Given the offset
   (uniform), each path's 32 bits are uniform and independent of its other random numbers, as
   random bits would be, so every path keeps its exact density and the image stays unbiased; the
   run's columns are stratified; and paths taken one after another (a fused work-item's chunk, a
   wavefront's slots) read the same or neighbouring columns, where random bits read the table all
   over (measured: README "Render throughput"). The column/alias choice must stay random: lattice
   low bits would repeat within a batch and correlate with the column. pick_step 0 (tests that
   probe the emitters): the path's own random bits. Requires shift < 32. */
static inline uint emission_pick_bits(const global RenderParams* params, ulong path, uint random_bits,
                                      uint shift)
{
    if (!params->pick_step)
        return random_bits;
    const uint low = (1u << shift) - 1u;
    return ((params->pick_offset + (uint)path * params->pick_step) & ~low) | (random_bits & low);
}

/* The sun's direction of travel: its axis, or uniform in its cone (u1, u2 in [0, 1)). */
static inline float3 sun_direction(const global RenderParams* params, float u1, float u2)
{
    const float3 axis = params->sun_dir.xyz;
    return params->sun_dir.w < 1.0f ? sample_cone(axis, params->sun_dir.w, u1, u2) : axis;
}

/* Direction of travel for table entry `entry` (u1, u2 uniform in [0, 1)). *weight: for the sun
   src->sun_weight, for sky cell k factor_k sin(theta) (lib/sky.h); the strategy multiplies in its
   geometric part. */
static inline float3 source_direction(const global RenderParams* params, const Sky* sky,
                                      const global SourceParams* src, uint entry, float u1,
                                      float u2, float3* weight)
{
    if (entry == 0) {
        *weight = src->sun_weight.xyz;
        return sun_direction(params, u1, u2);
    }
    float w;
    const float3 to_sky = sky_sample(sky, entry - 1, u1, u2, &w);
    *weight = (float3)(w);
    return -to_sky;
}

/* The start of the light's line through x along dir, outside the scene's bounding sphere. */
static inline float3 origin_outside(const global RenderParams* params, float3 x, float3 dir)
{
    const float back = length(x - params->sphere.xyz) + params->sphere.w;
    return x - dir * back;
}

/* The start of a ray along dir through point d (units of the sphere's radius) of the disk that
   covers the sphere, orthogonal to dir and spanned by t1, t2; 1 % beyond the sphere (adaptive
   emission's disk region). */
static inline float3 disk_ray_origin(const global RenderParams* params, float3 dir, float3 t1,
                                     float3 t2, float2 d_unit)
{
    const float radius = params->sphere.w;
    const float2 d = d_unit * radius;
    return params->sphere.xyz + d.x * t1 + d.y * t2 - dir * (1.01f * radius);
}

/* The start of a line along dir that enters the emission box (src->box_min, box_size: the
   scene's bounds, a little enlarged) at a point uniform over the box's silhouette seen along dir
   (DESIGN.md §3.1), moved back outside the bounding sphere; *area: the silhouette's area (m^2),
   A(dir) = sum over axes a of |dir_a| times the area of the faces normal to a. Every line into a
   convex box enters it through exactly one of the (up to) three faces that face the light, and a
   face's projection along dir is affine, so: a face by its share of A (u1), then uniform on it
   (the rest of u1, and u2). Lines that miss the box would miss every triangle, so none is drawn --
   the disk that covers the bounding sphere spent about half its paths on them. u1, u2 in [0, 1). */
static inline float3 box_line_origin(const global RenderParams* params, const global SourceParams* src,
                                     float3 dir, float u1, float u2, float* area)
{
    const float3 lo = src->box_min.xyz, e = src->box_size.xyz;
    const float3 a = fabs(dir) * (float3)(e.y * e.z, e.z * e.x, e.x * e.y);
    *area = a.x + a.y + a.z;
    float s = u1 * *area;
    float3 x;
    /* the entry face normal to axis k is at lo_k when the light travels towards +k. Rounding of
       the sum can carry s past the last face with a share: a face parallel to dir (a zero share)
       is never drawn, the last one with a share is, at its far edge (the clamps: no 0/0) */
    if (s < a.x || (a.y == 0.0f && a.z == 0.0f)) {
        const float v = fmin(s / fmax(a.x, FLT_MIN), 1.0f);
        x = (float3)(dir.x > 0.0f ? lo.x : lo.x + e.x, lo.y + e.y * v, lo.z + e.z * u2);
    } else if ((s -= a.x) < a.y || a.z == 0.0f) {
        const float v = fmin(s / a.y, 1.0f);
        x = (float3)(lo.x + e.x * u2, dir.y > 0.0f ? lo.y : lo.y + e.y, lo.z + e.z * v);
    } else {
        const float v = fmin((s - a.y) / a.z, 1.0f);
        x = (float3)(lo.x + e.x * v, lo.y + e.y * u2, dir.z > 0.0f ? lo.z : lo.z + e.z);
    }
    return origin_outside(params, x, dir);
}

/* A `uniform` line (DESIGN.md §3.1) from one Philox block: its first 32 bits (or the batch's
   lattice, emission_pick_bits) pick the sun or a sky cell from `table`, the other 96 give four
   24-bit uniforms for the direction and the point on the box's silhouette. *weight: the
   source's weight times the silhouette's area. */
static inline float3 uniform_line(const global RenderParams* params, const SourceTable* table, const Sky* sky,
                                  ulong path, RngBlock bits, float3* dir, float3* weight)
{
    const float4 u = rng_unit24x4(bits.y, bits.z, bits.w);
    const uint shift = table->params->alias_shift;
    const uint entry = alias_pick(table->alias, shift, emission_pick_bits(params, path, bits.x, shift));
    *dir = source_direction(params, sky, table->params, entry, u.z, u.w, weight);
    float area;
    const float3 origin = box_line_origin(params, table->params, *dir, u.x, u.y, &area);
    *weight *= area;
    return origin;
}

#endif /* FEN_EMIT_SOURCE_H */
