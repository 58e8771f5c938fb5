// fixed_point.h — the host's reading of the device's 128-bit fixed-point sums (pixels, cell and
// guide statistics, counters): kernels/lib/accumulate.h fixed_add128 keeps word[0] the low 64
// bits and word[1] the high ones.
#pragma once

#include <cstdint>

namespace fen {

// The sum held at word[0..1], in fixed-point units.
inline double fixed128(const std::uint64_t* word)
{
    return static_cast<double>(word[1]) * 18446744073709551616.0 + static_cast<double>(word[0]);
}

// An unsigned 128-bit integer as the device's accumulators hold it (kernels/lib/accumulate.h):
// the low and the high 64-bit word. Sums wrap modulo 2^128.
struct U128 {
    std::uint64_t lo = 0, hi = 0;
};

inline U128 add128(U128 a, U128 b)
{
    U128 s;
    s.lo = a.lo + b.lo;
    s.hi = a.hi + b.hi + (s.lo < a.lo ? 1u : 0u);
    return s;
}

inline U128 sub128(U128 a, U128 b)
{
    U128 d;
    d.lo = a.lo - b.lo;
    d.hi = a.hi - b.hi - (a.lo < b.lo ? 1u : 0u);
    return d;
}

// The sum held in a U128, in fixed-point units.
inline double fixed128(U128 v)
{
    const std::uint64_t w[2] = {v.lo, v.hi};
    return fixed128(w);
}

}  // namespace fen
