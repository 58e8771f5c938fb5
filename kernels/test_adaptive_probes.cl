/* test_adaptive_probes.cl — the adaptive strategy exposed to tests/kernels/adaptive_sampling_test.cpp.
 * Build with -DFEN_BVH_WIDTH. Not used by rendering.
 */
#include "lib/emit_adaptive.h"

/* Path i as emit_paths would start it: beta[i] (rgb weight, w: the quarter it was drawn from, as
   bits) and org[i] (xyz origin, w: 1 if kept, 0 if rejected), dir[i]. */
kernel void adaptive_emit_probe(global const RenderParams* params, global float4* beta,
                                global float4* org, global float4* dir, uint n, FEN_ADAPTIVE_ARGS)
{
    const uint i = get_global_id(0);
    if (i >= n)
        return;
    const AdaptiveEmitter e = FEN_ADAPTIVE_EMITTER;
    PathState p;
    const int kept = emit_adaptive(params, &e, i, &p);
    beta[i] = kept ? p.beta : (float4)(0.0f, 0.0f, 0.0f, p.beta.w);
    org[i] = kept ? (float4)(p.org.xyz, 1.0f) : (float4)(0.0f);
    dir[i] = kept ? p.dir : (float4)(0.0f);
}

/* basis[2 i], basis[2 i + 1] = travel_basis(n[i]) (lib/sampling.h): the adaptive disk's frame. */
kernel void travel_basis_probe(global const float4* n, global float4* basis, uint count)
{
    const uint i = get_global_id(0);
    if (i >= count)
        return;
    float3 t1, t2;
    travel_basis(n[i].xyz, &t1, &t2);
    basis[2 * i] = (float4)(t1, 0.0f);
    basis[2 * i + 1] = (float4)(t2, 0.0f);
}
