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

}  // namespace fen
