// context.cpp — context/queue creation, program building with full diagnostics, launch timing.
#include "cl/context.h"

#include <cstdlib>

#include "cl/cl_error.h"
#include "cl/kernel_source.h"
#include "util/error.h"

namespace fen { namespace ocl {

void KernelStats::record(const std::string& name, const cl::Event& done)
{
    pending_.emplace_back(name, done);
    if (pending_.size() > 4096)
        collect();
}

void KernelStats::collect()
{
    for (auto& [name, ev] : pending_) {
        ev.wait();
        const cl_ulong start = ev.getProfilingInfo<CL_PROFILING_COMMAND_START>();
        const cl_ulong end = ev.getProfilingInfo<CL_PROFILING_COMMAND_END>();
        Entry& e = entries_[name];
        e.launches += 1;
        e.deviceSeconds += end > start ? static_cast<double>(end - start) * 1e-9 : 0.0;
    }
    pending_.clear();
}

void KernelStats::reset()
{
    pending_.clear();
    entries_.clear();
}

const std::map<std::string, KernelStats::Entry>& KernelStats::entries()
{
    collect();
    return entries_;
}

std::string baseBuildOptions() { return "-cl-std=CL1.2"; }

Context::Context(const DeviceInfo& info) : info_(info)
{
    if (const char* env = std::getenv("FEN_LOCAL_SIZE"); env && *env) {
        char* end = nullptr;
        const unsigned long v = std::strtoul(env, &end, 10);
        if (*end != '\0' || v == 0 || v > 1024 || (v & (v - 1)) != 0)
            throw Error(cat("FEN_LOCAL_SIZE '", printable(env, 20), "': expected a power of two from 1 to 1024"));
        localSize_ = v;
    }
    try {
        context_ = cl::Context(info_.device);
        queue_ = cl::CommandQueue(context_, info_.device, CL_QUEUE_PROFILING_ENABLE);
    } catch (const cl::Error& e) {
        throw Error(cat("cannot open OpenCL device ", info_.label(), ": ", describe(e)));
    }
}

cl::Program Context::program(const std::string& mainFile, const std::vector<std::string>& defines)
{
    std::string options = baseBuildOptions();
    // OpenCL lets float division and sqrt be off by 2.5-3 ulp unless asked otherwise, and
    // NVIDIA's driver is: its triangle hits then differ from the CPU reference in the last bits
    // of t, u and v (measured, docs/results/gpu.md), and a ray through a shared edge can pick
    // the other neighbour. Asked for, both round as IEEE 754 does, on every device that can.
    if (info_.correctlyRoundedDivSqrt)
        options += " -cl-fp32-correctly-rounded-divide-sqrt";
    // Denormals are flushed to zero, as Embree asks its users to do for speed. perf put a quarter
    // of a CPU render's samples on plain adds and multiplies of float3 values, the mark of
    // microcode assists (~100 cycles each): on x86 a float3 lives in a 4-lane register whose
    // fourth lane keeps whatever bits were there before, and the bits of a small integer read as
    // a denormal. PoCL sets the CPU's flush-to-zero and denormals-are-zero modes for programs
    // built with this option (tested: Probes.CpuKernelsFlushDenormals); docs/results/denormals.md
    // has what it gains. What it changes in results: values below 1.2e-38, which no quantity of a
    // render reaches except on its way to nothing.
    options += " -cl-denorms-are-zero";
    for (const auto& d : defines)
        options += " -D" + d;
    const std::string key = mainFile + "|" + options;
    if (auto it = programs_.find(key); it != programs_.end())
        return it->second;

    // The source starts with FP_CONTRACT OFF (resolveKernelSource; a device that honours it is
    // checked by Probes.ProductsAndSumsRoundSeparately).
    const std::string source = resolveKernelSource(mainFile, defaultKernelReader());
    cl::Program prog(context_, source);
    const auto t0 = std::chrono::steady_clock::now();
    try {
        prog.build({info_.device}, options.c_str());
    } catch (const cl::Error& e) {
        std::string log;
        try {
            log = prog.getBuildInfo<CL_PROGRAM_BUILD_LOG>(info_.device);
        } catch (const cl::Error&) {
            log = "(no build log)";
        }
        throw Error(cat("kernel build of kernels/", mainFile, " failed on ", info_.label(),
                        " (", clErrorName(e.err()), ")\noptions: ", options, "\n", log));
    }
    buildSeconds_ +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    programs_.emplace(key, prog);
    return prog;
}

cl::Buffer Context::buffer(cl_mem_flags flags, std::size_t bytes, const char* what,
                           const void* initial)
{
    const std::size_t size = bytes == 0 ? 16 : bytes;
    if (size > info_.maxAllocBytes)
        throw Error(cat(what, " needs ", size >> 20, " MiB but ", info_.label(),
                        " allows at most ", info_.maxAllocBytes >> 20,
                        " MiB in one allocation"));
    try {
        if (initial && bytes > 0)
            return cl::Buffer(context_, flags | CL_MEM_COPY_HOST_PTR, size,
                              const_cast<void*>(initial));
        return cl::Buffer(context_, flags, size);
    } catch (const cl::Error& e) {
        throw Error(cat("cannot allocate ", what, " (", size >> 20, " MiB) on ", info_.label(),
                        ": ", describe(e)));
    }
}

} }  // namespace fen::ocl
