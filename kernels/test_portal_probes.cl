/* test_portal_probes.cl — portal emission exposed to tests/kernels/portal_sampling_test.cpp.
 * Build with -DFEN_BVH_WIDTH (the portals' BVH). Not used by rendering.
 */
#include "lib/bvh_traverse.h"
#include "lib/emit_portal.h"

/* out[i] = portal triangle chosen for direction dir (eq. 1), from the i-th random numbers. */
kernel void portal_pick_probe(global const float4* groups, global const uint* range,
                              global const ulong* triangle_cdf, uint group_count, float4 dir,
                              global uint* out, uint n, uint seed)
{
    const uint i = get_global_id(0);
    if (i >= n)
        return;
    Portals p;
    p.groups = groups;
    p.range = range;
    p.triangle_cdf = triangle_cdf;
    p.group_count = group_count;
    const RngBlock bits = rng_bits(seed, 0x13579bdu, i, 0, 0, 0);
    float scale;
    out[i] = portal_pick_triangle(&p, dir.xyz, bits.y, bits.x, &scale);
}

/* out[i] = the weight (rgb, before the camera) and alive flag of path i emitted by the portal
   strategy: what the emission kernel would put in the pool. */
kernel void portal_emit_probe(global const RenderParams* params, global const float* sky_theta,
                              global const float* sky_phi, global const float* sky_values,
                              global const float* sky_factor, global const ulong* source_cdf,
                              global const uint* source_guide, global const float4* portal_groups,
                              global const uint* portal_range, global const ulong* portal_cdf,
                              global const float4* portal_vertices,
                              global const BvhNode* portal_nodes,
                              global const TriPacket4* portal_packets, global float4* out, uint n)
{
    const uint i = get_global_id(0);
    if (i >= n)
        return;
    const Sky sky = sky_from(sky_theta, sky_phi, sky_values, sky_factor, params->sky_theta_nodes,
                             params->sky_phi_nodes);
    const SourceTable sources = source_table(source_cdf, source_guide, params->source_guide_shift);
    Portals portals;
    portals.groups = portal_groups;
    portals.range = portal_range;
    portals.triangle_cdf = portal_cdf;
    portals.vertices = portal_vertices;
    portals.nodes = portal_nodes;
    portals.packets = portal_packets;
    portals.group_count = params->portal_groups;
    PathState p;
    const int ok = emit_portal(params, &sky, &sources, &portals, i, &p);
    out[i] = ok ? (float4)(p.beta.xyz, 1.0f) : (float4)(0.0f);
}

/* out[i] = bvh_count_hits of rays[i] (portal emission's N(x, v)). */
kernel void count_probe(global const BvhNode* nodes, global const TriPacket4* packets,
                        global const Ray* rays, global uint* out, uint n)
{
    const uint i = get_global_id(0);
    if (i >= n)
        return;
    const Ray ray = rays[i];
    const RayPre r = ray_setup(ray.org_tmin.xyz, ray.dir_tmax.xyz, ray.org_tmin.w, ray.dir_tmax.w,
                               FEN_BVH_WIDTH);
    out[i] = bvh_count_hits(nodes, packets, &r);
}
