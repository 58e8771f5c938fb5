/* emit_uniform.h — the `uniform` emission strategy (DESIGN.md §3.1, the paper's "no optimisation").
 *
 * One Philox block per path (lib/emit_source.h uniform_line): its first 32 bits (or the batch's
 * lattice) pick an entry of the source table (the sun or a sky cell), the other 96 bits give four
 * 24-bit uniforms for the direction and the origin. Origin: uniform over the silhouette, seen
 * along the direction, of the box that bounds the scene (area A(v)), moved back outside the
 * bounding sphere. The weight is the emitted radiance over the density of (origin, direction):
 * for the sun E A(v) / P(sun), for the sky A(v) g / p(v) = A(v) factor_k sin(theta).
 * Host half: host/emission/uniform_strategy.h.
 */
#ifndef FEN_EMIT_UNIFORM_H
#define FEN_EMIT_UNIFORM_H

#include "lib/emit_source.h"

typedef struct {
    SourceTable sources;
    Sky sky;
} UniformEmitter;

/* The strategy's kernel arguments after (params, counters, paths), and how kernels/emit_*.cl assemble
   them. */
#define FEN_UNIFORM_ARGS                                                                        \
    global const SourceParams *source_params, global const uint *source_alias,                  \
        global const float *sky_theta, global const float *sky_phi, global const float *sky_values, \
        global const float *sky_factor
#define FEN_UNIFORM_EMITTER                                                                     \
    uniform_emitter(params, source_params, source_alias, sky_theta, sky_phi, sky_values, sky_factor)

static inline UniformEmitter uniform_emitter(const global RenderParams* params,
                                             const global SourceParams* source_params,
                                             const global uint* source_alias,
                                             const global float* sky_theta,
                                             const global float* sky_phi,
                                             const global float* sky_values,
                                             const global float* sky_factor)
{
    UniformEmitter e;
    e.sources.params = source_params;
    e.sources.alias = source_alias;
    e.sky = sky_from(sky_theta, sky_phi, sky_values, sky_factor, params->sky_theta_nodes,
                     params->sky_phi_nodes);
    return e;
}

/* Fills *p with path `path`; always emits. */
static inline int emit_uniform(const global RenderParams* params, const UniformEmitter* e,
                               ulong path, PathState* p)
{
    path_start(p, path);
    const RngBlock bits = rng_path_bits(params->seed, p->path_lo, p->path_hi, 0, FEN_RNG_EMIT);
    float3 dir, weight;
    p->org = (float4)(uniform_line(params, &e->sources, &e->sky, path, bits, &dir, &weight), 0.0f);
    p->dir = (float4)(dir, 0.0f);
    p->beta = (float4)(weight, 0.0f);
    return 1;
}

#endif /* FEN_EMIT_UNIFORM_H */
