// device.h — finding OpenCL devices and choosing one.
//
// Devices are numbered across all platforms in enumeration order; `--device` takes that number
// or a case-insensitive substring of "platform / device name (platform version)", so that
// `pocl` finds "Portable Computing Language" by its version string; with none given, the
// FEN_CL_DEVICE environment variable is used, else the first GPU, else the first CPU device.
#pragma once

#include <string>
#include <vector>

#include "cl/cl.h"

namespace fen { namespace ocl {

struct DeviceInfo {
    int index = -1;
    cl::Platform platform;
    cl::Device device;
    std::string platformName;
    std::string platformVersion;  // "OpenCL 3.0 PoCL 3.1 ...", "OpenCL 3.0 CUDA 13.0.88"
    std::string deviceName;
    std::string vendor;
    std::string deviceVersion;
    std::string driverVersion;
    std::string openclC;
    cl_device_type type = 0;
    cl_uint computeUnits = 0;
    cl_ulong globalMemBytes = 0;
    cl_ulong maxAllocBytes = 0;
    bool int64Atomics = false;
    // CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT: float / and sqrt can be asked to round as IEEE 754
    // does (Context::program asks), so kernels compute what the CPU references compute.
    bool correctlyRoundedDivSqrt = false;

    bool isGpu() const { return (type & CL_DEVICE_TYPE_GPU) != 0; }
    bool isCpu() const { return (type & CL_DEVICE_TYPE_CPU) != 0; }
    std::string typeName() const;
    std::string label() const;  // "platform / device"
    std::string matchText() const;  // what --device substrings are matched against
};

// All devices of all platforms. Throws fen::Error when there is no OpenCL platform at all.
std::vector<DeviceInfo> listDevices();

// The device named by `spec` (index or substring; "" = FEN_CL_DEVICE, else the default).
// `member`: the caller's rank among the processes on this machine (team/team.h): a substring
// several devices match, or no spec with several devices of the default's kind, gives member k
// the k-th of them (modulo their count), so that ranks spread over a machine's GPUs.
// Throws fen::Error naming the spec and listing what is available.
DeviceInfo selectDevice(const std::string& spec, int member = 0);

// Several devices for one render (DESIGN.md §9): "all" (every device listed), or a comma-separated
// list of indices or substrings (each as selectDevice takes it; none named twice); anything else is
// selectDevice(spec, member) alone.
std::vector<DeviceInfo> selectDevices(const std::string& spec, int member = 0);

// The default choice among `devices` (first GPU, else first CPU, else first); -1 if empty.
int defaultDeviceIndex(const std::vector<DeviceInfo>& devices);

} }  // namespace fen::ocl
