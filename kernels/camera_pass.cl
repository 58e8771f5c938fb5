/* camera_pass.cl — what the camera sees of the sky directly (DESIGN.md §6: a path from the sky
 * straight to the pinhole cannot be sampled from the light side, so it is traced from the camera).
 *
 * Work-item = pixel: spp[pixel] rays at uniform positions in the pixel (box filter; the host sets
 * the counts per batch, host/render/camera_sampler.h); each passes through glass (weight
 * T (1 - R), straight on) until it leaves the scene, where it picks up the sky's luminance, or hits
 * anything else, where it picks up nothing (that light is the light tracer's). Writes out[pixel] =
 * (mean over the samples (rgb), the sum of squared deviations of the samples' luminance from their
 * mean): the host estimates each pixel's per-sample variance from the latter. Welford's update,
 * since a sky pixel's luminance is thousands of cd/m^2 and sum(y^2) - n mean^2 in float would make
 * up variance where there is none.
 * Atomics: camera-ray counter (per work-group).
 */
#include "lib/accumulate.h"
#include "lib/bvh_traverse.h"
#include "lib/camera.h"
#include "lib/fresnel.h"
#include "lib/group_count.h"
#include "lib/ray_offset.h"
#include "lib/rng.h"
#include "lib/scene_access.h"
#include "lib/sky.h"

#define FEN_CAMERA_MAX_GLASS 16

/* Camera samples of one pixel; returns the rays traced, *cut the samples stopped by the glass
   limit. */
static inline uint camera_pixel(uint* cut, uint pixel, global const RenderParams* params, global const DevCamera* cam,
                                global const BvhNode* nodes, global const TriPacket4* packets,
                                global const uint* prim_material, global const DevMaterial* materials,
                                global const float* sky_theta, global const float* sky_phi,
                                global const float* sky_values, global const uint* spp, global float4* out)
{
    *cut = 0;
    if (pixel >= cam->width * cam->height)
        return 0;
    /* the camera pass only looks the sky up: no sampling weights */
    const Sky sky = sky_from(sky_theta, sky_phi, sky_values, (const global float*)0,
                             params->sky_theta_nodes, params->sky_phi_nodes);
    const uint px = pixel % cam->width, py = pixel / cam->width;
    float3 sum = (float3)(0.0f);
    float mean_y = 0.0f, m2_y = 0.0f; /* Welford: the samples' luminance */
    uint rays = 0;
    const uint n = spp[pixel];
    for (uint s = 0; s < n; ++s) {
        const float4 u = rng_camera(params->seed, pixel, s, params->batch);
        const float3 dir = camera_direction(cam, (float)px + u.x, (float)py + u.y);
        float3 org = cam->position.xyz;
        float3 weight = (float3)(1.0f);
        float3 value = (float3)(0.0f);
        int k = 0;
        for (; k < FEN_CAMERA_MAX_GLASS; ++k) {
            const RayPre r = ray_setup(org, dir, 0.0f, INFINITY, FEN_BVH_WIDTH);
            uint packet_lane;
            const Hit h = bvh_intersect_closest_at(nodes, packets, &r, &packet_lane);
            ++rays;
            if (h.prim == FEN_INVALID_ID) {
                value = weight * sky_eval(&sky, dir);
                break;
            }
            const global DevMaterial* m = materials + prim_material[h.prim];
            if (!material_is_glass(m))
                break;
            const global TriPacket4* p = packets + (packet_lane >> 2);
            const uint lane = packet_lane & 3u;
            const float3 ng = packet_normal(p, lane);
            weight *= m->transmission.xyz * (1.0f - fresnel_dielectric(dot(dir, ng), m->transmission.w));
            float offset_m;
            const float3 x = surface_point(packet_vertex(p, lane, 0), packet_vertex(p, lane, 1),
                                           packet_vertex(p, lane, 2), h.u, h.v, &offset_m);
            org = offset_ray_origin(x, offset_m, ng, dir);
        }
        *cut += k == FEN_CAMERA_MAX_GLASS;
        sum += value;
        const float y = rgb_luminance(value);
        const float delta = y - mean_y;
        mean_y += delta / (float)(s + 1u);
        m2_y += delta * (y - mean_y);
    }
    out[pixel] = (float4)(sum / (float)max(n, 1u), m2_y);
    return rays;
}

kernel void camera_pass(global const RenderParams* params, global const DevCamera* cam,
                        global const BvhNode* nodes, global const TriPacket4* packets,
                        global const uint* prim_material, global const DevMaterial* materials,
                        global const float* sky_theta, global const float* sky_phi,
                        global const float* sky_values, global const uint* spp, global float4* out,
                        volatile global ulong* counters)
{
    local uint rays_in_group;
    uint cut;
    const uint rays = camera_pixel(&cut, get_global_id(0), params, cam, nodes, packets, prim_material, materials,
                                   sky_theta, sky_phi, sky_values, spp, out);
    group_count_add(counters + FEN_CTR_CAMERA_RAYS, rays, &rays_in_group);
    group_count_add(counters + FEN_CTR_CAMERA_GLASS_CUT, cut, &rays_in_group);
}
