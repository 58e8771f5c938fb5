// memory_check_test.cpp — a render that cannot fit is refused before it allocates
// (render/memory_check.h): the film's largest buffer against the device's largest allocation,
// everything against its memory, the host's statistics against the host's memory.
#include <gtest/gtest.h>

#include "render/memory_check.h"
#include "util/error.h"

namespace fen {
namespace {

ocl::DeviceInfo device(std::uint64_t global, std::uint64_t maxAlloc)
{
    ocl::DeviceInfo d;
    d.globalMemBytes = global;
    d.maxAllocBytes = maxAlloc;
    return d;
}

std::string errorOf(const MemoryNeeds& n, const ocl::DeviceInfo& d, std::uint64_t host)
{
    try {
        checkMemoryNeeds(n, d, host);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(MemoryCheck, TheFilmMustFitTheDeviceAndTheHost)
{
    const std::uint64_t GB = 1000000000;
    // 640 x 480 and 2^16 slots: tens of MB, fine anywhere.
    const MemoryNeeds small = renderMemoryNeeds(640, 480, 1u << 16);
    EXPECT_LT(small.deviceBytes, 100 * 1000 * 1000u);
    EXPECT_EQ(errorOf(small, device(4 * GB, GB), 8 * GB), "");
    // 16384 x 16384: 48 bytes of accumulators a pixel, 12.9 GB in one buffer.
    const MemoryNeeds big = renderMemoryNeeds(16384, 16384, 1u << 16);
    EXPECT_EQ(big.largestBufferBytes, std::uint64_t{16384} * 16384 * 48);
    std::string e = errorOf(big, device(24 * GB, 6 * GB), 64 * GB);
    EXPECT_NE(e.find("--width/--height: the image needs a buffer of 12.8"), std::string::npos) << e;
    e = errorOf(big, device(14 * GB, 14 * GB), 64 * GB);
    EXPECT_NE(e.find("more than its 14 GB"), std::string::npos) << e;
    e = errorOf(big, device(140 * GB, 140 * GB), 24 * GB);
    EXPECT_NE(e.find("of host memory"), std::string::npos) << e;
    EXPECT_EQ(errorOf(big, device(140 * GB, 140 * GB), 64 * GB), "");
    // A pool of 2^26 slots (the most --pool takes) is gigabytes: named with the pixels.
    e = errorOf(renderMemoryNeeds(64, 64, std::uint64_t{1} << 26), device(2 * GB, 2 * GB), 64 * GB);
    EXPECT_NE(e.find("--pool"), std::string::npos) << e;
}

}  // namespace
}  // namespace fen
