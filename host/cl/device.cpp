// device.cpp — OpenCL platform/device enumeration and the --device rule (device.h).
#include "cl/device.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>

#include "cl/cl_error.h"
#include "util/error.h"

namespace fen { namespace ocl {

namespace {

std::string trimmed(std::string s)
{
    while (!s.empty() && (s.back() == '\0' || std::isspace(static_cast<unsigned char>(s.back()))))
        s.pop_back();
    size_t i = 0;
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i])))
        ++i;
    return s.substr(i);
}

std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

bool isIndex(const std::string& s)
{
    return !s.empty() && std::all_of(s.begin(), s.end(),
                                     [](unsigned char c) { return std::isdigit(c) != 0; });
}

std::string availableList(const std::vector<DeviceInfo>& devices)
{
    std::string s;
    for (const auto& d : devices)
        s += cat(s.empty() ? "" : "; ", d.index, ": ", d.label());
    return s.empty() ? "none" : s;
}

}  // namespace

std::string DeviceInfo::typeName() const
{
    if (type & CL_DEVICE_TYPE_GPU)
        return "GPU";
    if (type & CL_DEVICE_TYPE_CPU)
        return "CPU";
    if (type & CL_DEVICE_TYPE_ACCELERATOR)
        return "ACCEL";
    return "OTHER";
}

std::string DeviceInfo::label() const { return platformName + " / " + deviceName; }

std::string DeviceInfo::matchText() const { return label() + " (" + platformVersion + ")"; }

std::vector<DeviceInfo> listDevices()
{
    std::vector<cl::Platform> platforms;
    try {
        cl::Platform::get(&platforms);
    } catch (const cl::Error& e) {
        // The ICD loader answers CL_PLATFORM_NOT_FOUND_KHR when no driver is installed.
        throw Error(cat("no OpenCL platform found (", clErrorName(e.err()),
                        "); install an OpenCL driver, e.g. pocl-opencl-icd"));
    }
    if (platforms.empty())
        throw Error("no OpenCL platform found; install an OpenCL driver, e.g. pocl-opencl-icd");

    std::vector<DeviceInfo> out;
    for (const auto& p : platforms) {
        std::vector<cl::Device> devices;
        try {
            p.getDevices(CL_DEVICE_TYPE_ALL, &devices);
        } catch (const cl::Error&) {
            continue;  // a platform with no devices (CL_DEVICE_NOT_FOUND)
        }
        for (const auto& d : devices) {
            DeviceInfo info;
            info.index = static_cast<int>(out.size());
            info.platform = p;
            info.device = d;
            info.platformName = trimmed(p.getInfo<CL_PLATFORM_NAME>());
            info.platformVersion = trimmed(p.getInfo<CL_PLATFORM_VERSION>());
            info.deviceName = trimmed(d.getInfo<CL_DEVICE_NAME>());
            info.vendor = trimmed(d.getInfo<CL_DEVICE_VENDOR>());
            info.deviceVersion = trimmed(d.getInfo<CL_DEVICE_VERSION>());
            info.driverVersion = trimmed(d.getInfo<CL_DRIVER_VERSION>());
            info.openclC = trimmed(d.getInfo<CL_DEVICE_OPENCL_C_VERSION>());
            info.type = d.getInfo<CL_DEVICE_TYPE>();
            info.computeUnits = d.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
            info.globalMemBytes = d.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
            info.maxAllocBytes = d.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
            const std::string ext = d.getInfo<CL_DEVICE_EXTENSIONS>();
            info.int64Atomics = ext.find("cl_khr_int64_base_atomics") != std::string::npos;
            info.correctlyRoundedDivSqrt =
                (d.getInfo<CL_DEVICE_SINGLE_FP_CONFIG>() & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0;
            out.push_back(std::move(info));
        }
    }
    if (out.empty())
        throw Error("OpenCL platforms were found but none has a device");
    return out;
}

int defaultDeviceIndex(const std::vector<DeviceInfo>& devices)
{
    for (const auto& d : devices)
        if (d.isGpu())
            return d.index;
    for (const auto& d : devices)
        if (d.isCpu())
            return d.index;
    return devices.empty() ? -1 : 0;
}

DeviceInfo selectDevice(const std::string& specIn, int member)
{
    std::string spec = specIn;
    std::string origin = "--device";
    if (spec.empty()) {
        if (const char* env = std::getenv("FEN_CL_DEVICE"); env && *env) {
            spec = env;
            origin = "FEN_CL_DEVICE";
        }
    }
    const auto devices = listDevices();
    const auto nth = [&](const std::vector<const DeviceInfo*>& among) {
        return *among[static_cast<std::size_t>(std::max(member, 0)) % among.size()];
    };
    if (spec.empty()) {
        const DeviceInfo& first = devices[static_cast<size_t>(defaultDeviceIndex(devices))];
        std::vector<const DeviceInfo*> alike;  // the default's kind: GPUs, else CPUs
        for (const auto& d : devices)
            if (d.type == first.type)
                alike.push_back(&d);
        return member == 0 ? first : nth(alike);
    }
    if (isIndex(spec)) {
        const long i = std::strtol(spec.c_str(), nullptr, 10);
        if (i >= 0 && i < static_cast<long>(devices.size()))
            return devices[static_cast<size_t>(i)];
        throw Error(cat("no OpenCL device has index ", spec, " (", origin, "); available: ",
                        availableList(devices)));
    }
    const std::string needle = lower(spec);
    std::vector<const DeviceInfo*> matches;
    for (const auto& d : devices)
        if (lower(d.matchText()).find(needle) != std::string::npos)
            matches.push_back(&d);
    if (!matches.empty())
        return nth(matches);
    throw Error(cat("no OpenCL device matches ", origin, " '", spec, "'; available: ",
                    availableList(devices)));
}

std::vector<DeviceInfo> selectDevices(const std::string& spec, int member)
{
    if (spec == "all")
        return listDevices();
    if (spec.find(',') == std::string::npos)
        return {selectDevice(spec, member)};
    std::vector<DeviceInfo> chosen;
    std::size_t at = 0;
    for (;;) {
        const std::size_t comma = spec.find(',', at);
        const std::string one = spec.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
        if (one.empty())
            throw Error(cat("--device '", spec, "': an empty item in the list"));
        const DeviceInfo d = selectDevice(one);
        for (const DeviceInfo& c : chosen)
            if (c.index == d.index)
                throw Error(cat("--device '", spec, "': device ", d.index, " (", d.label(), ") is named twice"));
        chosen.push_back(d);
        if (comma == std::string::npos)
            break;
        at = comma + 1;
    }
    return chosen;
}

} }  // namespace fen::ocl
