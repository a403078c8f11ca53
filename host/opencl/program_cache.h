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
/// ~/.cache/tessera, else "tessera-cache-<uid>" in $TMPDIR (or /tmp), made mode 0700 and
/// used only while this user owns it and no one else may write to it; empty (no cache)
/// otherwise. Each entry is checked whole (length, checksum, key) before it is used.
std::filesystem::path program_cache_dir();

struct ProgramBuild {
    cl::Program program;
    bool from_cache = false;
    std::string options;
};

/// Builds kernel source `name` (see load_kernel_source) for `dev` with `defines` plus
/// the fixed options "-cl-std=CL1.2" (no fast-math or finite-math flags: NaN/Inf must
/// survive) and "-cl-fp32-correctly-rounded-divide-sqrt" where the device supports it
/// (else -DTS_INEXACT_DIV_SQRT, which widens the traversal's box bound). The cache key is a 64-bit FNV-1a hash of the expanded source, the options
/// and the platform, device and driver names and versions. A stale or corrupt cache
/// entry is ignored and rebuilt. Throws BuildError (util/error.h) with the full build log
/// on a compile error.
ProgramBuild build_program(const cl::Context& ctx, const ClDeviceInfo& dev, const std::string& name,
                           const std::vector<std::string>& defines);

/// The first line of an OpenCL build log that reports an error, trimmed: clang's form,
/// "error:", first, else any line that says "error"; "" if none does. A build failure's
/// message leads with it (the whole log follows).
std::string build_log_first_error(const std::string& log);

/// The problem with running kernel `kernel` on device `device` at work-group size
/// `required` (TS_WORKGROUP_SIZE, fixed: the kernels declare reqd_work_group_size) when
/// the device allows at most `limit` work-items for it (CL_KERNEL_WORK_GROUP_SIZE, which
/// drivers lower for kernels with much private memory): a message naming the kernel, the
/// device and both numbers, or empty when it fits.
std::string kernel_limit_problem(const std::string& kernel, const std::string& device, size_t limit, size_t required);

/// Queries `k`'s limits on `dev` and throws RuntimeError with kernel_limit_problem's
/// message when the kernel cannot run at TS_WORKGROUP_SIZE.
void check_kernel_limits(const cl::Kernel& k, const ClDeviceInfo& dev, const std::string& name);

}  // namespace tessera
