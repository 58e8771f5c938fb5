/* test_guide_probes.cl — the first-bounce guide's device half (lib/guide.h) exposed to
 * tests/kernels/guide_sampling_test.cpp. Not used by rendering.
 */
#include "lib/guide.h"

/* n draws from (learned) slot `slot`'s table: out[i] = (u1, u2, d(b), as_float(global leaf)). */
kernel void guide_sample_probe(global const GuideParams* guide_params, global const uint* guide_tables,
                               uint slot, uint seed, uint n, global float4* out)
{
    const uint i = get_global_id(0);
    if (i >= n)
        return;
    const Guide g = {guide_params, guide_tables, 0, 0};
    if (!(guide_record_of(&g, slot).w & FEN_GUIDE_LEARNED)) { /* only a learned slot has columns */
        out[i] = (float4)(0.0f);
        return;
    }
    uint key;
    float d;
    const float2 sq = guide_sample(&g, guide_record_of(&g, slot), rng_bits(seed, 0u, i, 0u, 0u, FEN_RNG_GUIDE),
                                   &key, &d);
    out[i] = (float4)(sq, d, as_float(key));
}

/* The slot of vertex i at x[i] with normal n[i]. */
kernel void guide_slot_probe(global const GuideParams* guide_params, global const uint* guide_tables,
                             global const float4* x, global const float4* n, uint count, global uint* slot)
{
    const uint i = get_global_id(0);
    const Guide g = {guide_params, guide_tables, 0, 0};
    if (i < count)
        slot[i] = guide_slot(&g, x[i].xyz, n[i].xyz);
}

/* The global leaf of slot `slot`'s tree that point sq[i] of the square lies in. */
kernel void guide_leaf_probe(global const GuideParams* guide_params, global const uint* guide_tables,
                             uint slot, global const float2* sq, uint count, global uint* leaf)
{
    const uint i = get_global_id(0);
    if (i >= count)
        return;
    const Guide g = {guide_params, guide_tables, 0, 0};
    leaf[i] = guide_leaf(&g, guide_record_of(&g, slot), sq[i]);
}

/* Weight-window arrivals (lib/guide.h guide_arrive): work-item i adds a[i per + k] to the sums of
   slot slot[i per + k], k = 0 .. per - 1 in order, held in registers and flushed at its end
   (hold = 1, as the fused kernel does) or each added at once (hold = 0, as shade.cl does). */
kernel void guide_arrive_probe(global const GuideParams* guide_params, volatile global ulong* window_stats,
                               global const uint* slot, global const float* a, uint per, uint count, uint hold,
                               volatile global ulong* counters)
{
    const uint i = get_global_id(0);
    if (i >= count)
        return;
    HeldArrivals held;
    held_arrivals_init(&held);
    const Guide g = {guide_params, 0, window_stats, hold ? &held : 0};
    for (uint k = 0; k < per; ++k)
        guide_arrive(&g, slot[i * per + k], a[i * per + k], counters);
    guide_arrivals_flush(&g);
}

/* Camera contributions recorded (lib/guide.h guide_record): contribution i of luminance y[i], made
   by a path whose record names leaf key[i] (g = 1), window word window[i] (slot | flags) and
   connection word opening[i] (lib/opening_aim.h), at the window statistics' scale `scale`. */
kernel void guide_record_probe(volatile global ulong* guide_stats, volatile global ulong* window_stats,
                               global const uint* key, global const float* y, global const uint* window,
                               global const uint* opening, float scale, uint count, volatile global ulong* counters)
{
    const uint i = get_global_id(0);
    if (i < count)
        guide_record(guide_stats, window_stats, 1.0f, key[i], y[i], scale, window[i], opening[i], counters);
}
