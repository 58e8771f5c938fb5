// memory_check.cpp — a render's memory, reckoned before it is allocated (memory_check.h).
#include "render/memory_check.h"

#include <algorithm>

#include <unistd.h>

#include "render/film.h"
#include "render/path_loop.h"
#include "util/error.h"

namespace fen {

namespace {

std::string gigabytes(std::uint64_t b) { return cat(static_cast<double>(b) / 1e9, " GB"); }

}  // namespace

MemoryNeeds renderMemoryNeeds(int width, int height, std::uint64_t poolSlots)
{
    const std::uint64_t px = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
    MemoryNeeds n;
    const std::uint64_t accum = px * Film::kWordsPerPixel * 8, camera = px * (16 + 4);  // image, samples
    n.deviceBytes = accum + camera + poolSlots * poolSlotBytes();
    n.largestBufferBytes = std::max<std::uint64_t>(accum, poolSlots * poolLargestSlotBytes());
    // The host: the batch sums (rgb and Y^2), the batch's image and the mean, the noise image, the
    // EXRs and PNGs being encoded: about 16 doubles a pixel.
    n.hostBytes = px * 16 * 8;
    return n;
}

std::uint64_t physicalMemory(std::uint64_t given)
{
    if (given)
        return given;
    const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
    return pages > 0 && page > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) : 0;
}

void checkMemoryNeeds(const MemoryNeeds& n, const ocl::DeviceInfo& device, const std::string& what,
                      const std::string& advice, std::uint64_t hostBytes)
{
    hostBytes = physicalMemory(hostBytes);
    if (device.maxAllocBytes > 0 && n.largestBufferBytes > device.maxAllocBytes)
        throw Error(cat(what, " need a buffer of ", gigabytes(n.largestBufferBytes), " on the device, more than its largest (",
                        gigabytes(device.maxAllocBytes), "): ", advice));
    if (device.globalMemBytes > 0 && n.deviceBytes > device.globalMemBytes)
        throw Error(cat(what, " need ", gigabytes(n.deviceBytes), " on the device, more than its ",
                        gigabytes(device.globalMemBytes), ": ", advice));
    if (hostBytes > 0 && n.hostBytes > hostBytes)
        throw Error(cat(what, " need ", gigabytes(n.hostBytes), " of host memory, more than this machine's ",
                        gigabytes(hostBytes), ": ", advice));
}

void checkMemoryNeeds(const MemoryNeeds& n, const ocl::DeviceInfo& device, std::uint64_t hostBytes)
{
    hostBytes = physicalMemory(hostBytes);
    if (device.maxAllocBytes > 0 && n.largestBufferBytes > device.maxAllocBytes)
        throw Error(cat("--width/--height: the image needs a buffer of ", gigabytes(n.largestBufferBytes),
                        " on the device, more than its largest (", gigabytes(device.maxAllocBytes),
                        "): render fewer pixels (or lower --pool)"));
    if (device.globalMemBytes > 0 && n.deviceBytes > device.globalMemBytes)
        throw Error(cat("--width/--height and --pool: the film and path pool need ", gigabytes(n.deviceBytes),
                        " on the device, more than its ", gigabytes(device.globalMemBytes),
                        ": render fewer pixels or lower --pool"));
    if (hostBytes > 0 && n.hostBytes > hostBytes)
        throw Error(cat("--width/--height: the image's statistics need ", gigabytes(n.hostBytes),
                        " of host memory, more than this machine's ", gigabytes(hostBytes), ": render fewer pixels"));
}

}  // namespace fen
