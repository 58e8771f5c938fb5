// memory_check.h — what a render will allocate, reckoned before it allocates (README "Nothing
// lost"): the film (the device's 128-bit accumulators and camera image; the host's batch sums and
// the image copies around them) and the path pool, against the device's memory and largest
// buffer and the host's physical memory. A render that cannot fit fails at once, in one line
// naming the option to change, instead of after seconds of work with "out of memory".
#pragma once

#include <cstdint>
#include <string>

#include "cl/device.h"

namespace fen {

struct MemoryNeeds {
    std::uint64_t deviceBytes = 0;        // all the render's film and pool buffers
    std::uint64_t largestBufferBytes = 0; // the largest of them
    std::uint64_t hostBytes = 0;
};

MemoryNeeds renderMemoryNeeds(int width, int height, std::uint64_t poolSlots);

// Throws fen::Error when `needs` exceeds `device` (its memory, its largest buffer) or the host's
// physical memory; `hostBytes` 0 asks the system.
void checkMemoryNeeds(const MemoryNeeds& needs, const ocl::DeviceInfo& device, std::uint64_t hostBytes = 0);
// The same for another part of a render: errors say "<what> need ..." and end with `advice`.
void checkMemoryNeeds(const MemoryNeeds& needs, const ocl::DeviceInfo& device, const std::string& what,
                      const std::string& advice, std::uint64_t hostBytes = 0);

}  // namespace fen
