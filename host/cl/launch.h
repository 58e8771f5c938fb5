// launch.h — setting kernel arguments with an arity check, and named, timed launches.
//
// Every launch has a name; its device time lands in Context::stats() (reported by the commands'
// --json output). Work is 1-D: `n` work-items rounded up to the local size; kernels guard
// `gid >= n` themselves (OpenCL 1.2 has no non-uniform work-groups).
#pragma once

#include <string>
#include <type_traits>

#include "cl/context.h"
#include "util/error.h"

namespace fen { namespace ocl {

// Sets arguments first, first + 1, ... of `kernel`; they must be its last ones (the arity is
// checked). Buffers must outlive the launch: clSetKernelArg does not retain memory objects, so a
// temporary cl::Buffer would be freed before the kernel runs (seen as a PoCL crash) -- refused at
// compile time.
template <class... Args>
void setKernelArgsFrom(cl::Kernel& kernel, cl_uint first, Args&&... args)
{
    static_assert(((!std::is_same_v<std::decay_t<Args>, cl::Buffer> || std::is_lvalue_reference_v<Args>) && ...),
                  "pass buffers that outlive the launch, not temporaries");
    const cl_uint expected = kernel.getInfo<CL_KERNEL_NUM_ARGS>();
    if (expected != first + sizeof...(Args))
        throw Error(cat("kernel ", kernel.getInfo<CL_KERNEL_FUNCTION_NAME>(), " takes ", expected,
                        " arguments, the host passes ", first + sizeof...(Args)));
    cl_uint i = first;
    (kernel.setArg(i++, args), ...);
}

// Sets all arguments of `kernel`.
template <class... Args>
void setKernelArgs(cl::Kernel& kernel, Args&&... args)
{
    setKernelArgsFrom(kernel, 0, std::forward<Args>(args)...);
}

inline cl::Event launch(Context& ctx, const cl::Kernel& kernel, const std::string& name,
                        std::size_t n, std::size_t local = 0)
{
    cl::Event done;
    if (n == 0)
        return done;
    if (local == 0)
        local = ctx.localSize();
    const std::size_t global = (n + local - 1) / local * local;
    ctx.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(global), cl::NDRange(local),
                                     nullptr, &done);
    ctx.stats().record(name, done);
    return done;
}

} }  // namespace fen::ocl
