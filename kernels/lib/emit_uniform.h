/* emit_uniform.h — the `uniform` emission strategy (DESIGN.md §3.1, the paper's "no optimisation").
 *
 * Source: the sun if the path's first 32 random bits fall below sun_threshold, else the sky (host:
 * in proportion to their flux through the emission disk; weights use the exact threshold / 2^32). Direction: the sun's (or uniform in its cone when it has an angular
 * radius), or the sky sampled by sky_sample(). Origin: uniform on the disk of radius R orthogonal
 * to the direction that covers the scene's bounding sphere, moved back outside it. The weight is
 * the emitted radiance over the density of (origin, direction): for the sun E pi R^2 / P(sun), for
 * the sky (pi R^2 / p_sky) g / p(v) = (pi R^2 / p_sky) factor_k sin(theta).
 */
#ifndef FEN_EMIT_UNIFORM_H
#define FEN_EMIT_UNIFORM_H

#include "lib/rng.h"
#include "lib/sky.h"
#include "shared/fen_render.h"

static inline PathState emit_uniform(const global RenderParams* params, const Sky* sky, ulong path)
{
    PathState p;
    p.path_lo = (uint)path;
    p.path_hi = (uint)(path >> 32);
    p.depth = 0;
    const RngBlock bits = rng_path_bits(params->seed, p.path_lo, p.path_hi, 0, FEN_RNG_EMIT_A);
    const float4 ua = rng_to_floats(bits);
    const float4 ub = rng_path(params->seed, p.path_lo, p.path_hi, 0, FEN_RNG_EMIT_B);
    float3 dir;
    if (bits.x < params->sun_threshold || params->sun_threshold == 0xFFFFFFFFu) {
        const float3 axis = params->sun_dir.xyz;
        dir = params->sun_dir.w < 1.0f ? sample_cone(axis, params->sun_dir.w, ua.y, ua.z) : axis;
        p.beta = params->sun_weight;
        p.flags = FEN_PATH_ALIVE | FEN_PATH_FROM_SUN;
    } else {
        float w;
        dir = -sky_sample(sky, bits.y, ua.z, ua.w, &w);
        p.beta = (float4)(params->sky_weight.x * w);
        p.flags = FEN_PATH_ALIVE;
    }
    const float radius = params->sphere.w;
    float3 t1, t2;
    orthonormal_basis(dir, &t1, &t2);
    const float2 d = sample_disk(ub.x, ub.y) * radius;
    const float3 origin = params->sphere.xyz + d.x * t1 + d.y * t2 - dir * (1.01f * radius);
    p.org = (float4)(origin, 0.0f);
    p.dir = (float4)(dir, 0.0f);
    p.beta.w = 0.0f;
    return p;
}

#endif /* FEN_EMIT_UNIFORM_H */
