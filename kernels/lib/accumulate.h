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

#include "shared/fen_emission.h"
#include "shared/fen_render.h"

static inline void counter_add(volatile global ulong* counters, int which, ulong v)
{
    atom_add(counters + which, v);
}

/* Splits x (fixed-point units, >= 0) into its high and low 64 bits; returns 0 when x is not below
   2^127 (or NaN). x = hi 2^64 + lo exactly: x has 24 significant bits, so x - hi 2^64 is a float too. */
static inline int fixed_parts(float x, ulong* hi, ulong* lo)
{
    if (!(x < 0x1p127f))
        return 0;
    *hi = convert_ulong_rtz(x * 0x1p-64f);
    *lo = convert_ulong_rte(x - (float)*hi * 0x1p64f);
    return 1;
}

/* Adds the 128-bit value hi 2^64 + lo to the accumulator (word[0] low, word[1] high). */
static inline void fixed_add_parts(volatile global ulong* word, ulong hi, ulong lo)
{
    ulong carry = 0ul;
    if (lo != 0ul) {
        const ulong old = atom_add(word, lo);
        carry = (old + lo < old) ? 1ul : 0ul;
    }
    if (hi + carry != 0ul)
        atom_add(word + 1, hi + carry);
}

/* Adds x (fixed-point units, >= 0) to the 128-bit accumulator (word[0] low, word[1] high);
   returns 0, adding nothing, when x is not below 2^127 (or NaN). */
static inline int fixed_add128(volatile global ulong* word, float x)
{
    ulong hi, lo;
    if (!fixed_parts(x, &hi, &lo))
        return 0;
    fixed_add_parts(word, hi, lo);
    return 1;
}

/* A 128-bit fixed-point sum a work-item holds in registers and adds to memory once
   (fixed_add_parts): the same integers summed in another order, so memory ends with the same
   bytes as if each value had been added there, with one atomic where there were many. */
typedef struct {
    ulong lo, hi;
} Fixed128;

static inline int fixed_add_held(Fixed128* s, float x)
{
    ulong hi, lo;
    if (!fixed_parts(x, &hi, &lo))
        return 0;
    s->lo += lo;
    s->hi += hi + (s->lo < lo ? 1ul : 0ul);
    return 1;
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
        if (c[k] == 0.0f)
            continue;
        if (!fixed_add128(accum + 6 * (ulong)pixel + 2 * k, c[k]))
            counter_add(counters, FEN_CTR_OVERFLOWS, 1);
    }
}

/* Luminance Y of linear rgb (DESIGN.md §1), as the host's Image::luminance weighs it. */
static inline float rgb_luminance(float3 c)
{
    return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

/* A learning strategy's statistics (DESIGN.md §3.3): the luminance of a contribution that reached
   the camera and its square, added to the emission cell its path started in, and a count. The
   cells' probabilities are what these steer, never the image's expectation, so a value out of
   range is dropped and counted (FEN_CTR_STATS_OVERFLOWS), costing efficiency, not bias. */
static inline void cell_stats_add(volatile global ulong* cell_stats, uint cell, float3 value,
                                  float scale, float scale_sq, volatile global ulong* counters)
{
    const float y = rgb_luminance(value);
    volatile global ulong* s = cell_stats + FEN_CELL_STATS_WORDS * (ulong)cell;
    if (!fixed_add128(s + FEN_CELL_SUM_LO, y * scale) || !fixed_add128(s + FEN_CELL_SUMSQ_LO, y * y * scale_sq))
        counter_add(counters, FEN_CTR_STATS_OVERFLOWS, 1);
    atom_inc(s + FEN_CELL_CONNECTIONS);
}

#endif /* FEN_ACCUMULATE_H */
