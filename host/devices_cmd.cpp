// devices_cmd.cpp — `fenestra devices`: every OpenCL platform/device, and which --device picks.
#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "cl/device.h"
#include "commands.h"

namespace fen {

int runDevices(bool json)
{
    const auto devices = ocl::listDevices();
    const int def = ocl::defaultDeviceIndex(devices);
    if (json) {
        nlohmann::json j = nlohmann::json::array();
        for (const auto& d : devices)
            j.push_back({{"index", d.index},
                         {"platform", d.platformName},
                         {"platform_version", d.platformVersion},
                         {"device", d.deviceName},
                         {"type", d.typeName()},
                         {"vendor", d.vendor},
                         {"version", d.deviceVersion},
                         {"driver", d.driverVersion},
                         {"opencl_c", d.openclC},
                         {"compute_units", d.computeUnits},
                         {"global_mem_bytes", d.globalMemBytes},
                         {"max_alloc_bytes", d.maxAllocBytes},
                         {"int64_atomics", d.int64Atomics},
                         {"correctly_rounded_divide_sqrt", d.correctlyRoundedDivSqrt},
                         {"default", d.index == def}});
        std::cout << j.dump(2) << "\n";
        return 0;
    }
    std::printf("  #  %-5s %4s %10s  %-22s %s\n", "type", "CUs", "memory", "OpenCL C", "platform / device");
    for (const auto& d : devices)
        std::printf("%s %2d  %-5s %4u %6.1f GiB  %-22s %s\n", d.index == def ? "*" : " ", d.index,
                    d.typeName().c_str(), d.computeUnits, d.globalMemBytes / 1073741824.0,
                    d.openclC.c_str(), d.label().c_str());
    std::printf("(* = used when --device is not given; --device takes an index or a name "
                "substring)\n");
    return 0;
}

}  // namespace fen
