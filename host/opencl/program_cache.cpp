#include "opencl/program_cache.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <system_error>
#include <unistd.h>

#include "kernels/shared/frame.h"
#include "opencl/kernel_source.h"
#include "util/error.h"

namespace tessera {
namespace fs = std::filesystem;

namespace {

uint64_t fnv1a(const std::string& s, uint64_t h = 1469598103934665603ull) {
    for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
    return h;
}

std::string hex(uint64_t v) {
    char b[17];
    std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(v));
    return b;
}

std::vector<unsigned char> read_file(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    if (!in) return {};
    return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), {});
}

// Best effort: a cache that cannot be written only costs a rebuild next time.
void write_file_atomic(const fs::path& p, const std::vector<unsigned char>& data) {
    std::error_code ec;
    fs::create_directories(p.parent_path(), ec);
    fs::path tmp = p;
    tmp += ".tmp." + std::to_string(::getpid());
    {
        std::ofstream out(tmp, std::ios::binary);
        if (!out) return;
        out.write(reinterpret_cast<const char*>(data.data()), static_cast<std::streamsize>(data.size()));
        if (!out) {
            out.close();
            fs::remove(tmp, ec);
            return;
        }
    }
    fs::rename(tmp, p, ec);
    if (ec) fs::remove(tmp, ec);
}

std::string build_log(const cl::Program& program, const cl::Device& device) {
    try {
        return program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device);
    } catch (const cl::Error&) {
        return "(no build log)";
    }
}

bool try_build(cl::Program& program, const cl::Device& device, const std::string& options) {
    try {
        program.build({device}, options.c_str());
        return true;
    } catch (const cl::Error&) {
        return false;
    }
}

}  // namespace

std::string kernel_limit_problem(const std::string& kernel, const std::string& device, size_t limit,
                                 size_t required) {
    if (limit >= required) return "";
    return "OpenCL kernel " + kernel + " on " + device + ": the device allows at most " + std::to_string(limit) +
           " work-items per work-group for it (CL_KERNEL_WORK_GROUP_SIZE), Tessera launches " +
           std::to_string(required) + " (TS_WORKGROUP_SIZE); use another --device or --backend embree";
}

void check_kernel_limits(const cl::Kernel& k, const ClDeviceInfo& dev, const std::string& name) {
    const size_t limit = k.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(dev.device);
    const std::string problem = kernel_limit_problem(name, dev.name, limit, TS_WORKGROUP_SIZE);
    if (!problem.empty()) throw RuntimeError(problem);
}

fs::path program_cache_dir() {
    if (const char* d = std::getenv("TESSERA_CACHE_DIR"); d && *d) return d;
    if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) return fs::path(d) / "tessera";
    if (const char* d = std::getenv("HOME"); d && *d) return fs::path(d) / ".cache" / "tessera";
    return fs::temp_directory_path() / "tessera-cache";
}

ProgramBuild build_program(const cl::Context& ctx, const ClDeviceInfo& dev, const std::string& name,
                           const std::vector<std::string>& defines) {
    const std::string source = load_kernel_source(name);
    ProgramBuild out;
    out.options = "-cl-std=CL1.2";
    // The traversal's conservative box test assumes correctly rounded division
    // (kernels/bvh_traverse.h); where the device cannot, it widens its bound instead.
    out.options += dev.correctly_rounded_div_sqrt ? " -cl-fp32-correctly-rounded-divide-sqrt" : " -DTS_INEXACT_DIV_SQRT";
    if (const char* extra = std::getenv("TESSERA_CL_OPTIONS"); extra && *extra) out.options += std::string(" ") + extra;
    for (const auto& d : defines) out.options += " " + d;
    const std::string key_text = source + "\n" + out.options + "\n" + dev.platform_name + "\n" +
                                 dev.name + "\n" + dev.version + "\n" + dev.driver;
    const fs::path cached = program_cache_dir() / (name + "-" + hex(fnv1a(key_text)) + ".bin");

    std::vector<unsigned char> binary = read_file(cached);
    if (!binary.empty()) {
        try {
            cl::Program::Binaries bins{binary};
            cl::Program p(ctx, {dev.device}, bins);
            if (try_build(p, dev.device, out.options)) {
                out.program = p;
                out.from_cache = true;
                return out;
            }
        } catch (const cl::Error&) {
            // Stale or corrupt entry: fall through to a build from source.
        }
    }

    cl::Program p(ctx, source);
    if (!try_build(p, dev.device, out.options))
        throw RuntimeError("OpenCL build of kernels/" + name + " failed on " + dev.name +
                           " with options \"" + out.options + "\":\n" + build_log(p, dev.device));
    try {
        auto bins = p.getInfo<CL_PROGRAM_BINARIES>();
        if (!bins.empty() && !bins[0].empty()) write_file_atomic(cached, bins[0]);
    } catch (const cl::Error&) {
        // Some drivers cannot return binaries; caching is then skipped.
    }
    out.program = p;
    return out;
}

}  // namespace tessera
