// Builds OpenCL programs and caches their binaries on disk, so a second run with the
// same source, options and device skips compilation (PoCL takes seconds per program).
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "opencl/cl.h"
#include "opencl/device.h"

namespace tessera {

/// Cache directory: $TESSERA_CACHE_DIR, else $XDG_CACHE_HOME/tessera, else
/// ~/.cache/tessera, else a "tessera-cache" directory in the system temp directory.
std::filesystem::path program_cache_dir();

struct ProgramBuild {
    cl::Program program;
    bool from_cache = false;
    std::string options;
};

/// Builds kernel source `name` (see load_kernel_source) for `dev` with `defines` plus
/// the fixed options "-cl-std=CL1.2" (no fast-math or finite-math flags: NaN/Inf must
/// survive). The cache key is a 64-bit FNV-1a hash of the expanded source, the options
/// and the platform, device and driver names and versions. A stale or corrupt cache
/// entry is ignored and rebuilt. Throws RuntimeError with the full build log on a
/// compile error.
ProgramBuild build_program(const cl::Context& ctx, const ClDeviceInfo& dev, const std::string& name,
                           const std::vector<std::string>& defines);

}  // namespace tessera
