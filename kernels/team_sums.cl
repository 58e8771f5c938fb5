/* team_sums.cl — a team's sums on the device (DESIGN.md §9; host: host/team/shared_sums.h).
 *
 * A summed buffer is records of `fields` fields, field f two words (a 128-bit fixed-point sum,
 * low word first: lib/accumulate.h) when bit f of `wide` is set, else one (a count). Before a pass
 * the host copies the buffer to `before`; after it, team_difference writes what this member's paths
 * added, one 128-bit value (low, high) per field, the count's in the low word; the host sums those
 * over the team and team_add writes before + sum back. Both wrap modulo 2^128 (2^64 for a count),
 * so the result is exactly the sum one process would hold. `zero_before`: the buffer held zeros
 * (cleared and not summed since) and `before` is not read.
 */

/* Where record r's words start in the buffer, and its fields in the differences. */
static inline void record_start(size_t r, uint fields, uint wide, size_t* word, size_t* field_word)
{
    *word = r * (fields + popcount(wide));
    *field_word = 2 * r * fields;
}

__kernel void team_difference(global const ulong* now, global const ulong* before, uint records, uint fields,
                              uint wide, uint zero_before, global ulong* delta)
{
    const size_t r = get_global_id(0);
    if (r >= records)
        return;
    size_t w, out;
    record_start(r, fields, wide, &w, &out);
    for (uint f = 0; f < fields; ++f) {
        const ulong lo = now[w], b_lo = zero_before ? 0ul : before[w];
        if ((wide >> f) & 1u) {
            const ulong hi = now[w + 1], b_hi = zero_before ? 0ul : before[w + 1];
            delta[out] = lo - b_lo;
            delta[out + 1] = hi - b_hi - (lo < b_lo ? 1ul : 0ul);
            w += 2;
        } else {
            delta[out] = lo - b_lo;
            delta[out + 1] = 0ul;
            w += 1;
        }
        out += 2;
    }
}

__kernel void team_add(global ulong* buffer, global const ulong* before, global const ulong* sums, uint records,
                       uint fields, uint wide, uint zero_before)
{
    const size_t r = get_global_id(0);
    if (r >= records)
        return;
    size_t w, in;
    record_start(r, fields, wide, &w, &in);
    for (uint f = 0; f < fields; ++f) {
        const ulong b_lo = zero_before ? 0ul : before[w];
        const ulong lo = b_lo + sums[in];
        buffer[w] = lo;
        if ((wide >> f) & 1u) {
            const ulong b_hi = zero_before ? 0ul : before[w + 1];
            buffer[w + 1] = b_hi + sums[in + 1] + (lo < b_lo ? 1ul : 0ul);
            w += 2;
        } else {
            w += 1;
        }
        in += 2;
    }
}
