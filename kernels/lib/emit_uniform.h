/* emit_uniform.h — the `uniform` emission strategy (DESIGN.md §3.1, the paper's "no optimisation").
 *
 * One Philox block per path: its first 32 bits pick an entry of the source table (the sun or a
 * sky cell, lib/emit_source.h), the other 96 bits give four 24-bit uniforms for the direction
 * and the origin. Origin: uniform on the disk of radius R orthogonal to the direction that
 * covers the scene's bounding sphere, moved back outside it. The weight is the emitted radiance
 * over the density of (origin, direction): for the sun E pi R^2 / P(sun), for the sky
 * pi R^2 g / p(v) = pi R^2 factor_k sin(theta).
 */
#ifndef FEN_EMIT_UNIFORM_H
#define FEN_EMIT_UNIFORM_H

#include "lib/emit_source.h"

static inline PathState emit_uniform(const global RenderParams* params, const Sky* sky,
                                     const SourceTable* sources, ulong path)
{
    PathState p;
    p.path_lo = (uint)path;
    p.path_hi = (uint)(path >> 32);
    p.depth = 0;
    p.flags = FEN_PATH_ALIVE;
    const RngBlock bits = rng_path_bits(params->seed, p.path_lo, p.path_hi, 0, FEN_RNG_EMIT);
    const float4 u = rng_unit24x4(bits.y, bits.z, bits.w);
    const uint entry = alias_pick(sources->alias, sources->shift, bits.x);
    float3 weight;
    const float3 dir = source_direction(params, sky, entry, u.z, u.w, &weight);
    if (entry != 0)
        weight *= params->sky_weight.x;
    const float radius = params->sphere.w;
    float3 t1, t2;
    orthonormal_basis(dir, &t1, &t2);
    const float2 d = sample_disk(u.x, u.y) * radius;
    const float3 origin = params->sphere.xyz + d.x * t1 + d.y * t2 - dir * (1.01f * radius);
    p.org = (float4)(origin, 0.0f);
    p.dir = (float4)(dir, 0.0f);
    p.beta = (float4)(weight, 0.0f);
    return p;
}

#endif /* FEN_EMIT_UNIFORM_H */
