// cl.h — the one place the OpenCL C++ bindings are configured and included.
//
// OpenCL 1.2 everywhere (PoCL reports C 1.2, so does NVIDIA), exceptions on: every failing call
// throws cl::Error, which main() turns into a one-line message (host/cl/cl_error.h names codes).
#pragma once

#define CL_HPP_TARGET_OPENCL_VERSION 120
#define CL_HPP_MINIMUM_OPENCL_VERSION 120
#define CL_HPP_ENABLE_EXCEPTIONS
#include <CL/opencl.hpp>
