/* camera_pass.cl — what the camera sees of the sky directly (DESIGN.md §6: a path from the sky
 * straight to the pinhole cannot be sampled from the light side, so it is traced from the camera).
 *
 * Work-item = pixel: params->camera_spp rays at uniform positions in the pixel (box filter); each
 * passes through glass (weight T (1 - R), straight on) until it leaves the scene, where it picks up
 * the sky's luminance, or hits anything else, where it picks up nothing (that light is the light
 * tracer's). Writes out[pixel] = mean over the samples (rgb). Atomics: camera-ray counter (per
 * work-group).
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
                                global const float* sky_values, global float4* out)
{
    *cut = 0;
    if (pixel >= cam->width * cam->height)
        return 0;
    /* the camera pass only looks the sky up: no sampling weights */
    const Sky sky = sky_from(sky_theta, sky_phi, sky_values, (const global float*)0,
                             params->sky_theta_nodes, params->sky_phi_nodes);
    const uint px = pixel % cam->width, py = pixel / cam->width;
    float3 sum = (float3)(0.0f);
    uint rays = 0;
    *cut = 0;
    for (uint s = 0; s < params->camera_spp; ++s) {
        const float4 u = rng_camera(params->seed, pixel, s, params->batch);
        const float3 dir = camera_direction(cam, (float)px + u.x, (float)py + u.y);
        float3 org = cam->position.xyz;
        float3 weight = (float3)(1.0f);
        int k = 0;
        for (; k < FEN_CAMERA_MAX_GLASS; ++k) {
            const RayPre r = ray_setup(org, dir, 0.0f, INFINITY, FEN_BVH_WIDTH);
            uint packet_lane;
            const Hit h = bvh_intersect_closest_at(nodes, packets, &r, &packet_lane);
            ++rays;
            if (h.prim == FEN_INVALID_ID) {
                sum += weight * sky_eval(&sky, dir);
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
    }
    out[pixel] = (float4)(sum / (float)max(params->camera_spp, 1u), 0.0f);
    return rays;
}

kernel void camera_pass(global const RenderParams* params, global const DevCamera* cam,
                        global const BvhNode* nodes, global const TriPacket4* packets,
                        global const uint* prim_material, global const DevMaterial* materials,
                        global const float* sky_theta, global const float* sky_phi,
                        global const float* sky_values, global float4* out,
                        volatile global ulong* counters)
{
    local uint rays_in_group;
    uint cut;
    const uint rays = camera_pixel(&cut, get_global_id(0), params, cam, nodes, packets, prim_material, materials,
                                   sky_theta, sky_phi, sky_values, out);
    group_count_add(counters + FEN_CTR_CAMERA_RAYS, rays, &rays_in_group);
    group_count_add(counters + FEN_CTR_CAMERA_GLASS_CUT, cut, &rays_in_group);
}
