/* test_uniform_probes.cl — `uniform` emission exposed to tests/kernels/uniform_sampling_test.cpp:
 * the lines over the emission box's silhouette alone, and whole emitted paths. Not used by
 * rendering.
 */
#include "lib/emit_uniform.h"

/* out[i].xyz = the origin of the i-th line along dir (lib/emit_source.h box_line_origin, from the
   i-th counter-based pair of uniforms), .w = the silhouette area it reports. */
kernel void box_line_probe(global const RenderParams* params, global const SourceParams* src, float dx,
                           float dy, float dz, global float4* out, uint n, uint seed)
{
    const uint i = get_global_id(0);
    if (i >= n)
        return;
    const float4 u = rng_floats(seed, 0x13579bdu, i, 0, 0, 0);
    float area;
    const float3 o = box_line_origin(params, src, (float3)(dx, dy, dz), u.x, u.y, &area);
    out[i] = (float4)(o, area);
}

/* Path i as emit_uniform starts it: its weight, origin and direction. */
kernel void uniform_emit_probe(global const RenderParams* params, global float4* beta, global float4* org,
                               global float4* dir, uint n, FEN_UNIFORM_ARGS)
{
    const uint i = get_global_id(0);
    if (i >= n)
        return;
    const UniformEmitter e = FEN_UNIFORM_EMITTER;
    PathState p;
    emit_uniform(params, &e, i, &p);
    beta[i] = p.beta;
    org[i] = p.org;
    dir[i] = p.dir;
}
