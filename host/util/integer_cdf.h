// integer_cdf.h — integer tables that draw an entry with exactly known probability (DESIGN.md
// §3.1): the emission strategies choose sources and cells with them, the first-bounce guide its
// boxes (device half: kernels/lib/sampling.h alias_pick). Weights use the probabilities the
// device realises, so a table's rounding costs variance, never bias.
#pragma once

#include <cstdint>
#include <vector>

namespace fen {

// An integer CDF over n entries (cdf[0] = 0 .. cdf[n] = 2^32): entry e has probability
// (cdf[e+1] - cdf[e]) / 2^32 exactly. The device draws from it with one read: an alias table of
// 2^(32 - aliasShift) >= n columns of 2^aliasShift values each (lib/sampling.h alias_pick;
// column j gives entry j to its first alias[2j] values and entry alias[2j+1] to the rest). The
// columns are filled with integers, so every entry keeps exactly its cdf units.
struct IntegerCdf {
    std::vector<std::uint64_t> cdf;
    std::vector<std::uint32_t> alias;  // per column: threshold, alias entry
    std::uint32_t aliasShift = 31;
    double probability(std::size_t e) const
    {
        return static_cast<double>(cdf[e + 1] - cdf[e]) / 4294967296.0;
    }
    // The entry the device draws for 32 random bits r (alias_pick); needs the alias table.
    std::uint32_t pick(std::uint32_t r) const;
};
// Units in proportion to `weight` (>= 0), at least one for every positive weight; `alias`: also
// the alias table, not needed for binary searches.
IntegerCdf makeIntegerCdf(const std::vector<double>& weight, bool alias = true);

}  // namespace fen
