/* test_opening_probes.cl — the opening aim's device half (lib/opening_aim.h) exposed to
 * tests/kernels/opening_aim_test.cpp. Not used by rendering.
 */
#include "lib/opening_aim.h"

/* n draws of the mixture at x (side n): out[i] = (v, p(v) / (cos / pi)), ratio 0 below the
   surface; w[0] = W, the triangles' total weight seen from x. */
kernel void aim_mixture_probe(global const OpeningAim* aim, float4 x, float4 n, uint seed, uint count,
                              global float4* out, global float* total_out)
{
    const uint i = get_global_id(0);
    if (i >= count)
        return;
    float w[FEN_AIM_MAX_TRIS];
    const float total = aim_weights(aim, x.xyz, n.xyz, w);
    if (i == 0u)
        total_out[0] = total;
    if (!(total > 0.0f)) {
        out[i] = (float4)(0.0f);
        return;
    }
    const float4 u = rng_to_floats(rng_bits(seed, 0u, i, 0u, 0u, FEN_RNG_SCATTER));
    const float3 cosine = sample_cosine_hemisphere(n.xyz, u.y, u.z);
    int aimed;
    float ratio;
    const float3 v = aim_mixture(aim, x.xyz, n.xyz, w, total, aim->cosine_share, cosine,
                                 rng_bits(seed, 0u, i, 0u, 0u, FEN_RNG_GUIDE), &aimed, &ratio);
    out[i] = (float4)(v, ratio);
}

/* Opening entries: path i, flags FEN_PATH_ALIVE | bounced[i] FEN_PATH_BRANCHED, crosses primitive
   prim[i] along dir[i] (normal ng[i]) with weight 1; code[i] = the flags' opening bits after it,
   the statistics in stats. */
kernel void opening_enter_probe(global const OpeningAim* aim, global const uint2* prims, volatile global ulong* stats,
                                global const uint* prim, global const float4* dir, global const float4* ng,
                                global const uint* bounced, uint count, global uint* code)
{
    const uint i = get_global_id(0);
    if (i >= count)
        return;
    const uint in = FEN_PATH_ALIVE | (bounced[i] ? FEN_PATH_BRANCHED : 0u);
    const uint flags = opening_enter(aim, prims, stats, in, prim[i], dir[i].xyz, ng[i].xyz,
                                     (float3)(1.0f), 1.0f);
    code[i] = path_opening(flags);
}
