// context.h — one OpenCL device in use: its context, an in-order profiling queue, the programs
// built for it, and the device time of every named kernel launch.
//
// Programs are built from kernels/ (kernel_source.h) with -cl-std=CL1.2 and -cl-denorms-are-zero,
// and never with -cl-fast-relaxed-math (it makes inf in the slab test undefined). A failed build
// throws fen::Error carrying the device, the options and the whole compiler log. PoCL keeps
// compiled kernels in its cache (POCL_CACHE_DIR), so a second run does not recompile.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "cl/cl.h"
#include "cl/device.h"

namespace fen { namespace ocl {

// Device time per named launch, read from profiling events.
class KernelStats {
public:
    struct Entry {
        std::uint64_t launches = 0;
        double deviceSeconds = 0.0;
    };
    void record(const std::string& name, const cl::Event& done);
    // Reads the timestamps of every recorded event (waits for them).
    void collect();
    void reset();
    const std::map<std::string, Entry>& entries();

private:
    std::vector<std::pair<std::string, cl::Event>> pending_;
    std::map<std::string, Entry> entries_;
};

class Context {
public:
    explicit Context(const DeviceInfo& info);

    const DeviceInfo& info() const { return info_; }
    const cl::Context& context() const { return context_; }
    const cl::Device& device() const { return info_.device; }
    cl::CommandQueue& queue() { return queue_; }
    KernelStats& stats() { return stats_; }
    // Work-items per work-group of a launch that names none: 64, or FEN_LOCAL_SIZE (a power of
    // two up to 1024, for measuring another size on a device; README "Kernels and OpenCL").
    std::size_t localSize() const { return localSize_; }

    // kernels/<mainFile> built with `-D` definitions (e.g. "FEN_BVH_WIDTH=8"); built once per
    // (file, definitions) in this process.
    cl::Program program(const std::string& mainFile, const std::vector<std::string>& defines = {});
    // Wall seconds spent in clBuildProgram so far (a PoCL cache hit makes this small).
    double buildSeconds() const { return buildSeconds_; }

    // An allocation checked against CL_DEVICE_MAX_MEM_ALLOC_SIZE, with the buffer's purpose in
    // the error; size 0 allocates a minimal buffer (OpenCL forbids empty ones).
    cl::Buffer buffer(cl_mem_flags flags, std::size_t bytes, const char* what,
                      const void* initial = nullptr);

private:
    DeviceInfo info_;
    cl::Context context_;
    cl::CommandQueue queue_;
    KernelStats stats_;
    std::map<std::string, cl::Program> programs_;
    double buildSeconds_ = 0.0;
    std::size_t localSize_ = 64;
};

// The options every program is built with, before the definitions.
std::string baseBuildOptions();

} }  // namespace fen::ocl
