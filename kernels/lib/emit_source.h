/* emit_source.h — what both emission strategies share: the source table (the sun, or one sky
 * cell, from 32 random bits with exact probabilities; host: emission_setup.h) and the direction
 * that source sends light in, with the source's part of the path weight.
 */
#ifndef FEN_EMIT_SOURCE_H
#define FEN_EMIT_SOURCE_H

#include "lib/rng.h"
#include "lib/sky.h"
#include "shared/fen_render.h"

typedef struct {
    const global uint* alias; /* entry 0 the sun, 1 + k sky cell k (lib/sampling.h alias_pick) */
    uint shift;
} SourceTable;

static inline SourceTable source_table(const global uint* alias, uint shift)
{
    SourceTable t;
    t.alias = alias;
    t.shift = shift;
    return t;
}

/* Direction of travel for table entry `entry` (u1, u2 uniform in [0, 1)). *weight: for the sun
   params->sun_weight, for sky cell k factor_k sin(theta) (lib/sky.h); the strategy multiplies in
   its own part (pi R^2, or the portals' projected area). */
static inline float3 source_direction(const global RenderParams* params, const Sky* sky, uint entry,
                                      float u1, float u2, float3* weight)
{
    if (entry == 0) {
        const float3 axis = params->sun_dir.xyz;
        *weight = params->sun_weight.xyz;
        return params->sun_dir.w < 1.0f ? sample_cone(axis, params->sun_dir.w, u1, u2) : axis;
    }
    float w;
    const float3 to_sky = sky_sample(sky, entry - 1, u1, u2, &w);
    *weight = (float3)(w);
    return -to_sky;
}

#endif /* FEN_EMIT_SOURCE_H */
