/* accumulate.h — adding a contribution to a pixel in 128-bit fixed point (DESIGN.md §4).
 *
 * Integer addition is associative, so the sum does not depend on the order in which threads add:
 * the same seed, scene and settings give a bit-identical image on a given device. 64 bits are
 * not enough: a light tracer's contributions span the pixel mean divided by the probability that
 * a path reaches that pixel -- with uniform emission, ten decades apart (measured: 5 % of the
 * default room's contributions overflowed a 64-bit scale fitted to pixel means). So each channel
 * is two 64-bit words, low and high: the low word takes the low 64 bits and a carry (detected from
 * the value atom_add returns) goes to the high word with the high 64 bits -- still exact, still
 * order-independent, and the high word is touched only for huge values or on a carry. The host
 * picks the scale (RenderParams.fixed_scale, 2^40 per reference luminance) and converts.
 * Contributions that are not finite or not below 2^127 units are counted (FEN_CTR_BAD_CONTRIBUTIONS,
 * FEN_CTR_OVERFLOWS) and must stay zero -- the tests check them.
 */
#ifndef FEN_ACCUMULATE_H
#define FEN_ACCUMULATE_H

#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable

#include "shared/fen_render.h"

static inline void counter_add(volatile global ulong* counters, int which, ulong v)
{
    atom_add(counters + which, v);
}

/* accum holds 6 ulongs per pixel: (low, high) for r, g and b. */
static inline void splat_rgb(volatile global ulong* accum, uint pixel, float3 value, float scale,
                             volatile global ulong* counters)
{
    if (!(isfinite(value.x) && isfinite(value.y) && isfinite(value.z)) ||
        value.x < 0.0f || value.y < 0.0f || value.z < 0.0f) {
        counter_add(counters, FEN_CTR_BAD_CONTRIBUTIONS, 1);
        return;
    }
    const float3 v = value * scale;
    const float c[3] = {v.x, v.y, v.z};
    for (int k = 0; k < 3; ++k) {
        const float x = c[k];
        if (x == 0.0f)
            continue;
        if (!(x < 0x1p127f)) {
            counter_add(counters, FEN_CTR_OVERFLOWS, 1);
            continue;
        }
        /* x = hi 2^64 + lo exactly: x has 24 significant bits, so x - hi 2^64 is a float too */
        const ulong hi = convert_ulong_rtz(x * 0x1p-64f);
        const ulong lo = convert_ulong_rte(x - (float)hi * 0x1p64f);
        volatile global ulong* word = accum + 6 * (ulong)pixel + 2 * k;
        const ulong old = atom_add(word, lo);
        const ulong carry = (old + lo < old) ? 1ul : 0ul;
        if (hi + carry != 0ul)
            atom_add(word + 1, hi + carry);
    }
}

#endif /* FEN_ACCUMULATE_H */
