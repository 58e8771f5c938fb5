/* test_probes.cl — thin kernels that expose library code to the tests (tests/kernels/).
 * Not used by rendering. Each kernel states what it writes.
 */
#include "shared/fen_layout.h"
#include "shared/fen_rng.h"
#include "lib/ray_offset.h"

/* out[2k], out[2k+1] = sizeof(struct), offsetof(struct, member) for the k-th FEN_SHARED_LAYOUT
   entry, measured on a real global pointer (portable where offsetof is not). */
kernel void layout_probe(global uint* out, global uchar* scratch)
{
    if (get_global_id(0) != 0)
        return;
    int k = 0;
#define FEN_PROBE(T, m)                                                                      \
    out[k++] = (uint)sizeof(T);                                                              \
    out[k++] = (uint)((global uchar*)&(((global T*)scratch)->m) - scratch);
    FEN_SHARED_LAYOUT(FEN_PROBE)
#undef FEN_PROBE
}

/* out[4i..4i+3] = Philox-4x32-10 of counter (i, c1, c2, c3) under key (k0, k1). */
kernel void rng_probe(global uint* out, uint n, uint c1, uint c2, uint c3, uint k0, uint k1)
{
    const uint i = get_global_id(0);
    if (i >= n)
        return;
    RngBlock ctr;
    ctr.x = i;
    ctr.y = c1;
    ctr.z = c2;
    ctr.w = c3;
    const RngBlock r = fen_philox4x32_10(ctr, k0, k1);
    out[4 * i + 0] = r.x;
    out[4 * i + 1] = r.y;
    out[4 * i + 2] = r.z;
    out[4 * i + 3] = r.w;
}

/* For hit i on triangle tri[3*i..3*i+2] (xyz in float4) with barycentrics bary[i].xy and a
   leaving direction dir[i].xyz: out[i] = the offset origin of the new ray. */
kernel void spawn_probe(global const float4* tri, global const float2* bary,
                        global const float4* dir, global float4* out, uint n)
{
    const uint i = get_global_id(0);
    if (i >= n)
        return;
    const float3 p0 = tri[3 * i].xyz, p1 = tri[3 * i + 1].xyz, p2 = tri[3 * i + 2].xyz;
    float offset_m;
    const float3 p = surface_point(p0, p1, p2, bary[i].x, bary[i].y, &offset_m);
    const float3 ng = normalize(cross(p1 - p0, p2 - p0)); /* unit, as surface_hit() gives it */
    out[i] = (float4)(offset_ray_origin(p, offset_m, ng, dir[i].xyz), offset_m);
}

/* ---- sampling routines (tests/kernels/sampling_test.cpp) ---- */
#include "lib/fresnel.h"
#include "lib/rng.h"
#include "lib/sampling.h"
#include "lib/sky.h"

/* out[i].xyz = a sample of routine `kind` from the i-th counter-based random quadruple:
   0 disk (x, y), 1 cosine hemisphere about +y, 2 cone about +y with cos_max = a,
   3 linear density on [0,1) with end values a, b (in x). */
kernel void sampling_probe(global float4* out, uint n, uint kind, float a, float b, uint seed)
{
    const uint i = get_global_id(0);
    if (i >= n)
        return;
    const float4 u = rng_floats(seed, 0x1234567u, i, 0, 0, 0);
    float4 r = (float4)(0.0f);
    if (kind == 0)
        r.xy = sample_disk(u.x, u.y);
    else if (kind == 1)
        r.xyz = sample_cosine_hemisphere((float3)(0.0f, 1.0f, 0.0f), u.x, u.y);
    else if (kind == 2)
        r.xyz = sample_cone((float3)(0.0f, 1.0f, 0.0f), a, u.x, u.y);
    else
        r.x = sample_linear(u.x, a, b);
    out[i] = r;
}

/* out[i] = entry chosen by alias_pick from 32 random bits. */
kernel void cdf_probe(global const uint* alias, uint shift,
                      global uint* out, uint n, uint seed)
{
    const uint i = get_global_id(0);
    if (i >= n)
        return;
    const RngBlock r = rng_bits(seed, 0x7654321u, i, 0, 0, 0);
    out[i] = alias_pick(alias, shift, r.x);
}

/* out[i].xyz = sampled direction towards the sky (cell from the integer table over the cells),
   .w = its weight factor_k sin(theta); lum[i] = sky_eval in the sampled direction. */
kernel void sky_probe(global const float* theta, global const float* phi, global const float* values,
                      global const uint* alias, uint alias_shift,
                      global const float* factor, uint nt, uint np,
                      global float4* out, global float* lum, uint n, uint seed)
{
    const uint i = get_global_id(0);
    if (i >= n)
        return;
    const Sky s = sky_from(theta, phi, values, factor, nt, np);
    const RngBlock bits = rng_bits(seed, 0x2468ace0u, i, 0, 0, 0);
    const float4 u = rng_unit24x4(bits.y, bits.z, bits.w);
    float w;
    const float3 d = sky_sample(&s, alias_pick(alias, alias_shift, bits.x), u.z, u.w, &w);
    out[i] = (float4)(d, w);
    lum[i] = sky_eval(&s, d);
}

/* out[i] = (sin(pi t), cos(pi t), acos(t)) of t = in[i] by lib/trig.h (acos only meant for |t| <= 1). */
kernel void trig_probe(global const float* in, global float4* out, uint n)
{
    const uint i = get_global_id(0);
    if (i >= n)
        return;
    float c;
    const float s = fen_sincospi(in[i], &c);
    out[i] = (float4)(s, c, fabs(in[i]) <= 1.0f ? fen_acos(in[i]) : 0.0f, 0.0f);
}

/* out[i] = fresnel_dielectric(cos_i[i], eta). */
kernel void fresnel_probe(global const float* cos_i, global float* out, uint n, float eta)
{
    const uint i = get_global_id(0);
    if (i < n)
        out[i] = fresnel_dielectric(cos_i[i], eta);
}


/* out[i] = alias_pick for the given 32-bit values (boundaries, not random draws). */
kernel void cdf_probe_at(global const uint* alias, uint shift,
                         global const uint* r, global uint* out, uint n)
{
    const uint i = get_global_id(0);
    if (i < n)
        out[i] = alias_pick(alias, shift, r[i]);
}

/* out[2i] = a[i] / b[i], out[2i+1] = sqrt(a[i]): the arithmetic the triangle test and the
   samplers rely on, to compare bit for bit with the host's IEEE 754 results. */
kernel void divsqrt_probe(global const float* a, global const float* b, global float* out, uint n)
{
    const uint i = get_global_id(0);
    if (i >= n)
        return;
    out[2 * i] = a[i] / b[i];
    out[2 * i + 1] = sqrt(a[i]);
}

/* out[i] = a[i] * b[i]: whether the program flushes denormal operands and results to zero
   (Context::program builds with -cl-denorms-are-zero; on a CPU each denormal operand otherwise
   costs a microcode assist). */
kernel void denormal_probe(global const float* a, global const float* b, global float* out, uint n)
{
    const uint i = get_global_id(0);
    if (i < n)
        out[i] = a[i] * b[i];
}

/* c = -(x*y) as the host rounds it: out[2i] = x*y + c in one statement, out[2i+1] = p + c with
   p = x*y in a statement of its own. Rounding the product and then the sum, as the host does, both
   are 0; a compiler that contracts the product and the sum into one fused multiply-add (one
   rounding) leaves the product's rounding error instead. Every program starts with
   FP_CONTRACT OFF (host/cl/kernel_source.cpp), which this checks a device honours. */
kernel void contract_probe(global const float* x, global const float* y, global const float* c,
                           global float* out, uint n)
{
    const uint i = get_global_id(0);
    if (i >= n)
        return;
    out[2 * i] = x[i] * y[i] + c[i];
    const float p = x[i] * y[i];
    out[2 * i + 1] = p + c[i];
}
