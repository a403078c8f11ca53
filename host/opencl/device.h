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
    /// CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT in CL_DEVICE_SINGLE_FP_CONFIG: the device can
    /// build with -cl-fp32-correctly-rounded-divide-sqrt (else division may be off by 2.5
    /// ulp and sqrt by 3, OpenCL 1.2 §7.4).
    bool correctly_rounded_div_sqrt = false;
    bool unified_memory = false;  ///< CL_DEVICE_HOST_UNIFIED_MEMORY: an integrated GPU (or a CPU)
};

/// The default device order: discrete GPUs, then integrated GPUs (host-unified memory),
/// then accelerators, CPUs and others; within a class more compute units first, then list
/// order. Returns indices into `devs`, best first. A discrete GPU has its own memory and
/// usually several times an integrated one's throughput, and ICD order is arbitrary (an
/// integrated GPU's platform is often listed first).
std::vector<size_t> rank_cl_devices(const std::vector<ClDeviceInfo>& devs);

/// Whether the OpenCL backend traces IGI's shadow rays on `d` as 16-ray packets with
/// explicit vector types (kernels/bvh_packet.h; docs/ray-batches.md §4) rather than one
/// ray per work-item: on CPU devices, whose OpenCL compilers (PoCL) cannot vectorise the
/// per-ray traversal loop across work-items. TESSERA_CL_PACKETS=0 overrides it per run.
inline bool cl_device_prefers_packets(const ClDeviceInfo& d) { return d.type == "CPU"; }

/// Whether the OpenCL backend builds its per-ray kernels for `d` with the short-stack
/// traversal (-DTS_GPU_TRAVERSAL, kernels/bvh_short_stack.h) instead of the full
/// 160-entry private stack, which a GPU keeps in slow scratch memory: on GPU devices.
/// BackendOptions::cl_gpu_variant (TESSERA_CL_GPU=1 / 0) forces it on or off on any device.
inline bool cl_device_prefers_short_stack(const ClDeviceInfo& d) { return d.type == "GPU"; }

/// Every device of every platform, in platform order. Empty if there is no platform
/// (no ICD installed); never throws for that.
std::vector<ClDeviceInfo> list_cl_devices();

/// Picks a device: `spec` empty → the best by rank_cl_devices;
/// all digits → that index; otherwise the first device whose "platform: name"
/// contains `spec` (case-insensitive). Throws RuntimeError listing the devices (and
/// suggesting --backend embree) when there is none or nothing matches.
ClDeviceInfo select_cl_device(const std::string& spec);

/// Why no device may be listed although an ICD is installed, as a clause to append to
/// "no OpenCL device found (...": PoCL lists none when it cannot write its kernel cache
/// (POCL_CACHE_DIR unset, and $XDG_CACHE_HOME, else $HOME, unwritable or under a missing
/// directory). "" when that is not the case.
std::string no_device_hint();

}  // namespace tessera
