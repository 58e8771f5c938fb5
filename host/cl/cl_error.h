// cl_error.h — names for OpenCL error codes (CL_INVALID_WORK_GROUP_SIZE beats -54).
#pragma once

#include <string>

#include "cl/cl.h"

namespace fen { namespace ocl {

const char* clErrorName(cl_int code);

// "clEnqueueNDRangeKernel failed: CL_INVALID_WORK_GROUP_SIZE (-54)"
std::string describe(const cl::Error& e);

} }  // namespace fen::ocl
