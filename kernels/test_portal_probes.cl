/* test_portal_probes.cl — portal emission exposed to tests/kernels/portal_sampling_test.cpp.
 * Build with -DFEN_BVH_WIDTH (the portals' BVH). Not used by rendering.
 */
#include "lib/bvh_traverse.h"
#include "lib/emit_portal.h"

/* out[i] = portal triangle chosen for direction dir in direction bin `bin` (eq. 1 averaged over the
   bin), from the i-th random numbers; FEN_INVALID_ID when the group drawn is edge-on to dir. */
kernel void portal_pick_probe(global const float4* groups, global const uint* group_alias,
                              global const float* group_ratio, global const uint* range,
                              global const ulong* triangle_cdf, uint group_count,
                              uint group_alias_shift, uint bin, float4 dir, global uint* out,
                              uint n, uint seed)
{
    const uint i = get_global_id(0);
    if (i >= n)
        return;
    /* choosing a triangle reads neither the vertices nor the BVH */
    const Portals p = portals_from(groups, group_alias, group_ratio, range, triangle_cdf, 0, 0, 0,
                                   group_count, group_alias_shift);
    const RngBlock bits = rng_bits(seed, 0x13579bdu, i, 0, 0, 0);
    float scale;
    out[i] = portal_pick_triangle(&p, bin, dir.xyz, bits.y, bits.x, &scale);
}

/* out[i] = the weight (rgb, before the camera) and alive flag of path i emitted by the portal
   strategy: what the emission kernel would put in the pool. */
kernel void portal_emit_probe(global const RenderParams* params, FEN_PORTAL_ARGS, global float4* out,
                              uint n)
{
    const uint i = get_global_id(0);
    if (i >= n)
        return;
    const PortalEmitter e = FEN_PORTAL_EMITTER;
    PathState p;
    const int ok = emit_portal(params, &e, i, &p);
    out[i] = ok ? (float4)(p.beta.xyz, 1.0f) : (float4)(0.0f);
}

/* out[i] = bvh_count_hits of rays[i] (portal emission's N(x, v)). */
kernel void count_probe(global const BvhNode* nodes, global const TriPacket4* packets,
                        global const Ray* rays, global uint* out, uint n)
{
    const uint i = get_global_id(0);
    if (i >= n)
        return;
    const RayPre r = ray_setup_stored(&rays[i], FEN_BVH_WIDTH);
    out[i] = bvh_count_hits(nodes, packets, &r);
}
