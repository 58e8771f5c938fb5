// summed_buffer.h — a device buffer of integer sums, described so that a team can add its
// members' copies exactly (team/shared_sums.h): records of fields, each field one 64-bit word (a
// count, summed modulo 2^64) or two (a 128-bit fixed-point sum, kernels/lib/accumulate.h: low
// word first). The film, the sensor cells and a learning strategy's statistics are such buffers.
#pragma once

#include <cstddef>
#include <vector>

#include "cl/cl.h"

namespace fen {

struct SummedBuffer {
    const cl::Buffer* buffer = nullptr;
    std::size_t records = 0;   // from the buffer's start
    std::vector<int> fields;   // words per field of a record, in order: 1 or 2
    std::size_t recordWords() const
    {
        std::size_t w = 0;
        for (int f : fields)
            w += static_cast<std::size_t>(f);
        return w;
    }
};

}  // namespace fen
