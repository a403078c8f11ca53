#include "opencl/program_cache.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <system_error>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>

#include "kernels/shared/frame.h"
#include "image/fatal_signal_cleanup.h"
#include "opencl/kernel_source.h"
#include "util/error.h"
#include "util/hash.h"

namespace tessera {
namespace fs = std::filesystem;

namespace {

std::string hex(uint64_t v) {
    char b[17];
    std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(v));
    return b;
}

// A cache entry: "TSCLBIN1", then u64 FNV-1a of the cache key's text, u64 byte count and
// u64 FNV-1a of the binary, then the binary. PoCL crashes on a truncated binary (a short
// file left by a crash: the writes are atomic but not synced), and a damaged one fails
// only at launch, so every entry is checked whole before the driver sees it.
constexpr char kEntryMagic[8] = {'T', 'S', 'C', 'L', 'B', 'I', 'N', '1'};
constexpr size_t kEntryHeader = sizeof kEntryMagic + 3 * sizeof(uint64_t);

std::vector<unsigned char> entry_bytes(uint64_t key, const std::vector<unsigned char>& binary) {
    const uint64_t head[3] = {key, uint64_t(binary.size()), fnv1a64(binary.data(), binary.size())};
    std::vector<unsigned char> e(kEntryHeader + binary.size());
    std::memcpy(e.data(), kEntryMagic, sizeof kEntryMagic);
    std::memcpy(e.data() + sizeof kEntryMagic, head, sizeof head);
    std::copy(binary.begin(), binary.end(), e.begin() + kEntryHeader);
    return e;
}

// The binary of the entry at `p` for `key`; empty when it is missing, unreadable, of
// another key, or not whole (any of which rebuilds it).
std::vector<unsigned char> read_entry(const fs::path& p, uint64_t key) {
    std::error_code ec;
    if (!fs::is_regular_file(p, ec)) return {};
    std::vector<unsigned char> e;
    try {
        std::ifstream in(p, std::ios::binary);
        if (!in) return {};
        e.assign(std::istreambuf_iterator<char>(in), {});
    } catch (const std::exception&) {
        return {};
    }
    uint64_t head[3];
    if (e.size() < kEntryHeader || !std::equal(kEntryMagic, kEntryMagic + sizeof kEntryMagic, e.begin())) return {};
    std::memcpy(head, e.data() + sizeof kEntryMagic, sizeof head);
    const size_t size = e.size() - kEntryHeader;
    if (head[0] != key || head[1] != size || head[2] != fnv1a64(e.data() + kEntryHeader, size)) return {};
    e.erase(e.begin(), e.begin() + kEntryHeader);
    return e;
}

// Best effort: a cache that cannot be written only costs a rebuild next time, said once.
void write_file_atomic(const fs::path& p, const std::vector<unsigned char>& data) {
    static bool told = false;
    const auto fail = [&](const std::string& why) {
        if (!told) std::fprintf(stderr, "tessera: note: OpenCL program cache %s not written (%s); later runs build "
                                        "again\n", p.parent_path().c_str(), why.c_str());
        told = true;
    };
    std::error_code ec;
    fs::create_directories(p.parent_path(), ec);
    if (ec) return fail(ec.message());
    fs::path tmp = p;
    tmp += ".tmp." + std::to_string(::getpid());
    const RemovedOnFatalSignal on_signal(tmp);  // a second Ctrl-C here leaves no half-written entry
    {
        std::ofstream out(tmp, std::ios::binary);
        if (!out) return fail("cannot create " + tmp.filename().string());
        out.write(reinterpret_cast<const char*>(data.data()), static_cast<std::streamsize>(data.size()));
        if (!out) {
            out.close();
            fs::remove(tmp, ec);
            return fail("write failed");
        }
    }
    fs::rename(tmp, p, ec);
    if (ec) {
        fail(ec.message());
        fs::remove(tmp, ec);
    }
}

// The shared temporary directory's cache is per user, made private, and used only while
// it is still ours and writable by us alone: a file another user put there would be run.
bool private_to_us(const fs::path& dir) {
    std::error_code ec;
    if (!fs::exists(dir, ec)) fs::create_directories(dir, ec);
    struct stat st {};
    if (::lstat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != ::geteuid()) return false;
    // Ours (not through a link): made private if it is not, e.g. by an older build.
    if ((st.st_mode & (S_IRWXG | S_IRWXO)) != 0) fs::permissions(dir, fs::perms::owner_all, ec);
    return ::lstat(dir.c_str(), &st) == 0 && (st.st_mode & (S_IWGRP | S_IWOTH)) == 0;
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

// The build log's first line that reports an error, trimmed; empty if none does. It leads
// the failure's message: the whole log (warnings, the driver's own lines) follows. Clang's
// form, "error:", first (PoCL's and NVIDIA's logs use it; a warning's text may say
// "errors"), else any line that says "error".
std::string build_log_first_error(const std::string& log) {
    for (const char* mark : {"error:", "error"}) {
        std::istringstream in(log);
        std::string line;
        while (std::getline(in, line)) {
            if (line.find(mark) == std::string::npos) continue;
            const size_t a = line.find_first_not_of(" \t"), b = line.find_last_not_of(" \t\r");
            return line.substr(a, b - a + 1);
        }
    }
    return "";
}

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
    std::error_code ec;
    fs::path tmp = fs::temp_directory_path(ec);  // $TMPDIR; a bad one is not this run's problem
    if (ec) tmp = "/tmp";
    const fs::path dir = tmp / ("tessera-cache-" + std::to_string(::geteuid()));
    if (private_to_us(dir)) return dir;
    static bool told = false;
    if (!told)
        std::fprintf(stderr, "tessera: note: OpenCL program cache %s is not a private directory of this user; no "
                             "programs are cached (set TESSERA_CACHE_DIR)\n", dir.c_str());
    told = true;
    return {};
}

ProgramBuild build_program(const cl::Context& ctx, const ClDeviceInfo& dev, const std::string& name,
                           const std::vector<std::string>& defines) {
    const std::string source = load_kernel_source(name);
    ProgramBuild out;
    out.options = "-cl-std=CL1.2";
    // The traversal's conservative box test assumes correctly rounded division
    // (kernels/bvh_traverse.h); where the device cannot, it widens its bound instead.
    out.options += dev.correctly_rounded_div_sqrt ? " -cl-fp32-correctly-rounded-divide-sqrt" : " -DTS_INEXACT_DIV_SQRT";
    for (const auto& d : defines) out.options += " " + d;
    // The user's options last: one that takes an argument ("-I" at the end) cannot
    // swallow a define the scene needs (that rendered Sibenik untextured).
    if (const char* extra = std::getenv("TESSERA_CL_OPTIONS"); extra && *extra) out.options += std::string(" ") + extra;
    const std::string key_text = source + "\n" + out.options + "\n" + dev.platform_name + "\n" +
                                 dev.name + "\n" + dev.version + "\n" + dev.driver;
    const uint64_t key = fnv1a64(key_text.data(), key_text.size());
    const fs::path dir = program_cache_dir();
    // ".e1": the entry format, so a build that wrote raw binaries and this one, sharing a
    // cache, do not rebuild each other's entries on every run.
    const fs::path cached = dir.empty() ? fs::path() : dir / (name + "-" + hex(key) + ".e1.bin");

    std::vector<unsigned char> binary = cached.empty() ? std::vector<unsigned char>() : read_entry(cached, key);
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
    {
        const std::string log = build_log(p, dev.device), first = build_log_first_error(log);
        throw BuildError("OpenCL build of kernels/" + name + " failed on " + dev.name +
                         (first.empty() ? "" : ": " + first) + "\n  options: " + out.options + "\n  build log:\n" +
                         log);
    }
    try {
        auto bins = p.getInfo<CL_PROGRAM_BINARIES>();
        if (!cached.empty() && !bins.empty() && !bins[0].empty()) write_file_atomic(cached, entry_bytes(key, bins[0]));
    } catch (const cl::Error&) {
        // Some drivers cannot return binaries; caching is then skipped.
    }
    out.program = p;
    return out;
}

}  // namespace tessera
