/* shade_path.h — what happens at a path's hit (DESIGN.md §2), for the wavefront's shade.cl and the
 * fused kernel (lib/fused_kernel.h) alike:
 *  - thin glass: specular reflection with probability R(theta) (Fresnel, one interface), else
 *    straight through with weight *= T (expected weight R + (1 - R) T, as the model says);
 *  - Lambertian: connect to the pinhole -- if the camera sees this side of the surface, the
 *    contribution C = beta (rho/pi) |cos theta_x| / (d^2 A_pix cos^3 theta_c) goes into *c for
 *    lib/connect_path.h to test and splat -- then scatter cosine-weighted on the side the light
 *    arrived at. From interaction params->rr_depth on, Russian roulette: survive with probability
 *    q = max(rho), weight *= rho / q (its largest channel keeps its value); before it, every path
 *    goes on with weight *= rho (unbiased either way; which is more efficient: README "Path
 *    termination");
 *  - a path reaching params->max_depth interactions dies (counted, with its flux: a bias that is
 *    reported; the default cap is high enough that only endless paths meet it).
 * Invariant: the result depends only on the path, its hit and its random numbers (keyed by path
 * index and depth), never on which kernel or slot runs it.
 */
#ifndef FEN_SHADE_PATH_H
#define FEN_SHADE_PATH_H

#include "lib/accumulate.h"
#include "lib/camera.h"
#include "lib/fresnel.h"
#include "lib/ray_offset.h"
#include "lib/rng.h"
#include "lib/sampling.h"
#include "lib/scene_access.h"

/* Shades path *p at hit *h (a surface, not a miss). Sets *c to the camera connection, its pixel
   FEN_INVALID_ID when there is none. Returns 1 if the path goes on, with its next ray in *p. */
static inline int shade_path(global const RenderParams* params, PathState* p, const SurfaceHit* h,
                             global const uint* prim_material, global const DevMaterial* materials,
                             global const DevCamera* cam, Connection* c, volatile global ulong* counters)
{
    c->org.w = as_float(FEN_INVALID_ID);
    const uint prim = as_uint(h->normal.w);
    const global DevMaterial* m = materials + prim_material[prim];
    const float3 ng = h->normal.xyz;
    const float offset_m = h->pos.w;
    const float3 x = h->pos.xyz;
    const float3 dir = p->dir.xyz;
    const float4 u = rng_path(params->seed, p->path_lo, p->path_hi, p->depth + 1, FEN_RNG_SCATTER);
    float3 next;
    int alive = 1;

    if (material_is_glass(m)) {
        const float cos_i = dot(dir, ng);
        if (u.x < fresnel_dielectric(cos_i, m->transmission.w)) {
            next = dir - 2.0f * cos_i * ng;
        } else {
            next = dir;
            p->beta.xyz *= m->transmission.xyz;
        }
    } else {
        /* the side of the surface the light arrived at */
        const float3 n = dot(dir, ng) < 0.0f ? ng : -ng;
        const float3 albedo = m->albedo.xyz;
        float cos_c, dist2;
        const uint pixel = camera_project(cam, x, &cos_c, &dist2);
        if (pixel != FEN_INVALID_ID) {
            const float3 to_cam = cam->position.xyz - x;
            const float cos_x = dot(to_cam, n) / sqrt(dist2);
            if (cos_x > 0.0f) {
                const float3 value = p->beta.xyz * albedo * (cos_x / (FEN_PI * dist2 * cam->up.w *
                                                                       cos_c * cos_c * cos_c));
                if (value.x > 0.0f || value.y > 0.0f || value.z > 0.0f) {
                    const float3 o = offset_ray_origin(x, offset_m, ng, to_cam);
                    c->org = (float4)(o, as_float(pixel));
                    c->to_cam = (float4)(cam->position.xyz - o, 0.0f);
                    c->value = (float4)(value, p->beta.w); /* the emission cell */
                }
            }
        }
        if (p->depth < params->rr_depth) {
            p->beta.xyz *= albedo;
            alive = albedo.x > 0.0f || albedo.y > 0.0f || albedo.z > 0.0f;
            next = sample_cosine_hemisphere(n, u.y, u.z);
        } else {
            const float q = fmax(albedo.x, fmax(albedo.y, albedo.z));
            if (u.x < q) {
                p->beta.xyz *= albedo / q;
                next = sample_cosine_hemisphere(n, u.y, u.z);
            } else {
                alive = 0;
                next = dir;
            }
        }
    }
    p->depth += 1;
    if (alive && p->depth >= params->max_depth) {
        /* the cap guards against endless paths; what it removes is measured (rare: direct atomics) */
        alive = 0;
        counter_add(counters, FEN_CTR_MAX_DEPTH, 1);
        const float y = 0.2126f * p->beta.x + 0.7152f * p->beta.y + 0.0722f * p->beta.z;
        fixed_add128(counters + FEN_CTR_CUT_FLUX_LO, y * params->fixed_scale);
    }
    if (!alive)
        return 0;
    p->org = (float4)(offset_ray_origin(x, offset_m, ng, next), 0.0f);
    p->dir = (float4)(next, 0.0f);
    return 1;
}

#endif /* FEN_SHADE_PATH_H */
