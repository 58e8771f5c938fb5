// fnv.h — FNV-1a, 64 bits: the hash behind checkpoint checksums and fingerprints
// (render/checkpoint.cpp), the adaptive grid's checksum (emission/adaptive_grid.cpp) and the
// sensors' fingerprint (render/renderer.cpp). Not cryptographic: it tells an edited or other
// state from this one, it does not resist a forger.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

namespace fen {

struct Fnv {
    std::uint64_t h = 1469598103934665603ull;
    void add(const void* data, std::size_t n)
    {
        const unsigned char* b = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < n; ++i)
            h = (h ^ b[i]) * 1099511628211ull;
    }
    // A value's bytes as they lie in memory.
    template <class T>
    void value(const T& v)
    {
        add(&v, sizeof v);
    }
    // A string's length, then its bytes.
    void text(const std::string& s)
    {
        value(s.size());
        add(s.data(), s.size());
    }
};

// A 64-bit hash as fingerprints and keys write it: 16 lower-case hex digits.
inline std::string hex64(std::uint64_t v)
{
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(v));
    return hex;
}

}  // namespace fen
