// OpenCL platform and device discovery and selection.
#pragma once
#include <string>
#include <vector>

#include "opencl/cl.h"

namespace tessera {

struct ClDeviceInfo {
    int index = 0;            ///< position in list_cl_devices(), across all platforms
    cl::Platform platform;
    cl::Device device;
    std::string platform_name;
    std::string name;
    std::string version;      ///< CL_DEVICE_VERSION
    std::string driver;       ///< CL_DRIVER_VERSION
    std::string type;         ///< "CPU", "GPU", "accelerator" or "other"
    unsigned compute_units = 0;
    unsigned long long global_mem = 0;     ///< bytes
    unsigned long long max_alloc = 0;      ///< CL_DEVICE_MAX_MEM_ALLOC_SIZE, bytes
};

/// Every device of every platform, in platform order. Empty if there is no platform
/// (no ICD installed); never throws for that.
std::vector<ClDeviceInfo> list_cl_devices();

/// Picks a device: `spec` empty → the first GPU if any, else the first device;
/// all digits → that index; otherwise the first device whose "platform: name"
/// contains `spec` (case-insensitive). Throws RuntimeError listing the devices (and
/// suggesting --backend embree) when there is none or nothing matches.
ClDeviceInfo select_cl_device(const std::string& spec);

}  // namespace tessera
