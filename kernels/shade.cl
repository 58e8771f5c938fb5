/* shade.cl — wavefront stage 3: what happens at each live path's hit (DESIGN.md §2).
 *
 * Work-item i, slot i:
 *  - miss: the path leaves the scene and dies;
 *  - thin glass: specular reflection with probability R(theta) (Fresnel, one interface), else
 *    straight through with weight *= T (expected weight R + (1 - R) T, as the model says);
 *  - Lambertian: connect to the pinhole -- if the camera sees this side of the surface, the
 *    contribution C = beta (rho/pi) |cos theta_x| / (d^2 A_pix cos^3 theta_c) goes into
 *    connections[i] for connect.cl to test and splat -- then scatter cosine-weighted on the side
 *    the light arrived at, surviving Russian roulette with probability q = max(rho) (weight
 *    *= rho / q, so its largest channel keeps its value);
 *  - a path reaching params->max_depth interactions dies (counted, with its flux: a bias that is
 *    reported; the default cap is high enough that only endless paths meet it).
 * Writes paths[i] and connections[i] (pixel FEN_INVALID_ID when there is none). Atomics: the
 * alive counter (per work-group), the max-depth counter.
 */
#include "lib/accumulate.h"
#include "lib/camera.h"
#include "lib/fresnel.h"
#include "lib/group_count.h"
#include "lib/ray_offset.h"
#include "lib/rng.h"
#include "lib/sampling.h"
#include "lib/scene_access.h"

/* Shades slot i; returns 1 if its path goes on. */
static inline uint shade_one(uint i, global const RenderParams* params, global PathState* paths,
                             global const SurfaceHit* hits, global const uint* prim_material,
                             global const DevMaterial* materials, global const DevCamera* cam,
                             global Connection* connections, volatile global ulong* counters)
{
    if (i >= params->pool_size)
        return 0;
    connections[i].org.w = as_float(FEN_INVALID_ID);
    PathState p = paths[i];
    if (!(p.flags & FEN_PATH_ALIVE))
        return 0;
    const SurfaceHit h = hits[i];
    const uint prim = as_uint(h.normal.w);
    if (prim == FEN_INVALID_ID) {
        paths[i].flags = 0;
        return 0;
    }
    const global DevMaterial* m = materials + prim_material[prim];
    const float3 ng = h.normal.xyz;
    const float offset_m = h.pos.w;
    const float3 x = h.pos.xyz;
    const float3 dir = p.dir.xyz;
    const float4 u = rng_path(params->seed, p.path_lo, p.path_hi, p.depth + 1, FEN_RNG_SCATTER);
    float3 next;
    int alive = 1;

    if (material_is_glass(m)) {
        const float cos_i = dot(dir, ng);
        if (u.x < fresnel_dielectric(cos_i, m->transmission.w)) {
            next = dir - 2.0f * cos_i * ng;
        } else {
            next = dir;
            p.beta.xyz *= m->transmission.xyz;
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
                const float3 value = p.beta.xyz * albedo * (cos_x / (FEN_PI * dist2 * cam->up.w *
                                                                      cos_c * cos_c * cos_c));
                if (value.x > 0.0f || value.y > 0.0f || value.z > 0.0f) {
                    Connection c;
                    const float3 o = offset_ray_origin(x, offset_m, ng, to_cam);
                    c.org = (float4)(o, as_float(pixel));
                    c.to_cam = (float4)(cam->position.xyz - o, 0.0f);
                    c.value = (float4)(value, p.beta.w); /* the emission cell */
                    connections[i] = c;
                }
            }
        }
        const float q = fmax(albedo.x, fmax(albedo.y, albedo.z));
        if (u.x < q) {
            p.beta.xyz *= albedo / q;
            next = sample_cosine_hemisphere(n, u.y, u.z);
        } else {
            alive = 0;
            next = dir;
        }
    }
    p.depth += 1;
    if (alive && p.depth >= params->max_depth) {
        /* the cap guards against endless paths; what it removes is measured (rare: direct atomics) */
        alive = 0;
        counter_add(counters, FEN_CTR_MAX_DEPTH, 1);
        const float y = 0.2126f * p.beta.x + 0.7152f * p.beta.y + 0.0722f * p.beta.z;
        fixed_add128(counters + FEN_CTR_CUT_FLUX_LO, y * params->fixed_scale);
    }
    if (!alive) {
        paths[i].flags = 0;
        return 0;
    }
    p.org = (float4)(offset_ray_origin(x, offset_m, ng, next), 0.0f);
    p.dir = (float4)(next, 0.0f);
    paths[i] = p;
    return 1;
}

kernel void shade_paths(global const RenderParams* params, global PathState* paths,
                        global const SurfaceHit* hits, global const uint* prim_material,
                        global const DevMaterial* materials, global const DevCamera* cam,
                        global Connection* connections, volatile global ulong* counters)
{
    local uint alive_in_group;
    const uint alive = shade_one(get_global_id(0), params, paths, hits, prim_material, materials,
                                 cam, connections, counters);
    group_count_add(counters + FEN_CTR_ALIVE, alive, &alive_in_group);
}
