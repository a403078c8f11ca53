#include "opencl/device.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <string>

#include "util/error.h"

namespace tessera {

std::string describe_cl_error(const cl::Error& e) {
    return std::string(e.what()) + " (OpenCL error " + std::to_string(e.err()) + ")";
}

namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

std::string trim(std::string s) {
    while (!s.empty() && (s.back() == '\0' || std::isspace(static_cast<unsigned char>(s.back()))))
        s.pop_back();
    return s;
}

std::string type_name(cl_device_type t) {
    if (t & CL_DEVICE_TYPE_GPU) return "GPU";
    if (t & CL_DEVICE_TYPE_CPU) return "CPU";
    if (t & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
    return "other";
}

// "[0] Portable Computing Language: pthread-...; [1] ...": one line, as every error is.
std::string device_list_text(const std::vector<ClDeviceInfo>& devs) {
    std::string s;
    for (const auto& d : devs)
        s += (s.empty() ? "" : "; ") + ("[" + std::to_string(d.index) + "] " + d.platform_name + ": " + d.name);
    return s;
}

}  // namespace

std::vector<ClDeviceInfo> list_cl_devices() {
    std::vector<ClDeviceInfo> out;
    std::vector<cl::Platform> platforms;
    try {
        cl::Platform::get(&platforms);
    } catch (const cl::Error&) {
        return out;  // CL_PLATFORM_NOT_FOUND_KHR: no ICD
    }
    for (const auto& p : platforms) {
        std::vector<cl::Device> devices;
        try {
            p.getDevices(CL_DEVICE_TYPE_ALL, &devices);
        } catch (const cl::Error&) {
            continue;  // a platform without devices
        }
        for (const auto& d : devices) {
            ClDeviceInfo i;
            i.index = static_cast<int>(out.size());
            i.platform = p;
            i.device = d;
            i.platform_name = trim(p.getInfo<CL_PLATFORM_NAME>());
            i.name = trim(d.getInfo<CL_DEVICE_NAME>());
            i.version = trim(d.getInfo<CL_DEVICE_VERSION>());
            i.driver = trim(d.getInfo<CL_DRIVER_VERSION>());
            i.type = type_name(d.getInfo<CL_DEVICE_TYPE>());
            i.compute_units = d.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
            i.global_mem = d.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
            i.max_alloc = d.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
            i.unified_memory = d.getInfo<CL_DEVICE_HOST_UNIFIED_MEMORY>() == CL_TRUE;
            i.correctly_rounded_div_sqrt =
                (d.getInfo<CL_DEVICE_SINGLE_FP_CONFIG>() & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0;
            // TESSERA_CL_MAX_ALLOC (bytes) lowers the limit, to try a small device's
            // limit on a large one (tests/cli/opencl_failure_test.cpp uses it).
            if (const char* cap = std::getenv("TESSERA_CL_MAX_ALLOC"); cap && *cap) {
                char* end = nullptr;
                errno = 0;
                const unsigned long long v = std::strtoull(cap, &end, 10);
                if (end == cap || *end != '\0' || errno == ERANGE || !std::isdigit(static_cast<unsigned char>(cap[0])))
                    throw InputError(std::string("TESSERA_CL_MAX_ALLOC=") + cap + ": expected a whole number of bytes");
                i.max_alloc = std::min(i.max_alloc, v);
            }
            out.push_back(std::move(i));
        }
    }
    return out;
}

std::vector<size_t> rank_cl_devices(const std::vector<ClDeviceInfo>& devs) {
    auto device_class = [](const ClDeviceInfo& d) {
        if (d.type == "GPU") return d.unified_memory ? 1 : 0;
        if (d.type == "accelerator") return 2;
        if (d.type == "CPU") return 3;
        return 4;
    };
    std::vector<size_t> order(devs.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        const int ca = device_class(devs[a]), cb = device_class(devs[b]);
        if (ca != cb) return ca < cb;
        return devs[a].compute_units > devs[b].compute_units;
    });
    return order;
}

namespace {

// Why PoCL could not make or write cache directory `dir` ("" where it can): the
// directory, or the part of its path that exists (PoCL makes the rest), must be a
// writable directory.
std::string unwritable_cache_dir(std::string dir) {
    while (::access(dir.c_str(), F_OK) != 0 && dir.find('/') != std::string::npos && dir != "/")
        dir = dir.substr(0, std::max<size_t>(dir.rfind('/'), 1));
    struct stat st {};
    if (::stat(dir.c_str(), &st) != 0) return dir.find('/') == std::string::npos ? "" : "cannot be made";
    if (!S_ISDIR(st.st_mode)) return dir + " is not a directory";
    if (::access(dir.c_str(), W_OK) != 0) return dir + " is not writable";
    return "";
}

}  // namespace

std::string no_device_hint() {
    // PoCL offers no device when it cannot make its kernel cache (a service account's
    // HOME=/nonexistent): an installed ICD that lists nothing. It takes POCL_CACHE_DIR,
    // else $XDG_CACHE_HOME/pocl, else $HOME/.cache/pocl.
    if (const char* pocl = std::getenv("POCL_CACHE_DIR"); pocl && *pocl) {
        const std::string why = unwritable_cache_dir(pocl);
        return why.empty() ? "" : std::string("; PoCL also lists none when it cannot write its cache: POCL_CACHE_DIR=") +
                                      pocl + ": " + why;
    }
    const char* xdg = std::getenv("XDG_CACHE_HOME");
    const bool use_xdg = xdg && *xdg;
    const char* home = use_xdg ? xdg : std::getenv("HOME");
    if (!home || !*home || unwritable_cache_dir(home).empty()) return "";
    return std::string("; PoCL also lists none when it cannot write its cache under ") +
           (use_xdg ? "XDG_CACHE_HOME (" : "HOME (") + home + "): set POCL_CACHE_DIR to a writable directory";
}

namespace {

// PoCL builds its kernels under POCL_CACHE_DIR where that is set: one it cannot write
// (a regular file, a read-only directory) failed the first kernel build with a multi-line
// "failed to build the program" that named neither. Refused when the device is chosen.
void check_pocl_cache_dir(const ClDeviceInfo& dev) {
    const char* dir = std::getenv("POCL_CACHE_DIR");
    if (!dir || !*dir || dev.platform_name.find("Portable Computing Language") == std::string::npos) return;
    if (const std::string why = unwritable_cache_dir(dir); !why.empty())
        throw RuntimeError(std::string("POCL_CACHE_DIR=") + dir + ": " + why + "; PoCL builds the kernels of " +
                           dev.name + " there (point it at a writable directory or unset it)");
}

// The device `spec` names (select_cl_device's contract).
ClDeviceInfo pick_cl_device(const std::string& spec) {
    auto devs = list_cl_devices();
    if (devs.empty())
        throw RuntimeError("no OpenCL device found (is an ICD such as pocl-opencl-icd installed?" + no_device_hint() +
                           "); use --backend embree to render on the CPU without OpenCL");
    if (spec.empty()) return devs[rank_cl_devices(devs).front()];
    if (std::all_of(spec.begin(), spec.end(), [](unsigned char c) { return std::isdigit(c); })) {
        // Digits only: an index (a run of them too long for one is out of range, not a crash).
        const size_t digits = spec.size() - std::min(spec.find_first_not_of('0'), spec.size());
        if (digits <= 9) {
            const size_t i = std::stoul(spec);
            if (i < devs.size()) return devs[i];
        }
    } else {
        const auto full = [&](size_t i) { return lower(devs[i].platform_name + ": " + devs[i].name); };
        std::vector<size_t> matches;
        for (size_t i = 0; i < devs.size(); ++i)
            if (full(i) == lower(spec) || lower(devs[i].name) == lower(spec)) return devs[i];  // exact: first
        for (size_t i = 0; i < devs.size(); ++i)
            if (full(i).find(lower(spec)) != std::string::npos) matches.push_back(i);
        // Devices of one name (identical GPUs) are as good as each other: the first.
        const bool one_name = std::all_of(matches.begin(), matches.end(), [&](size_t i) { return full(i) == full(matches[0]); });
        if (!matches.empty() && one_name) return devs[matches[0]];
        if (matches.size() > 1) {  // different devices: which one was meant is not ours to guess
            std::string names;
            for (size_t i : matches) names += (names.empty() ? "" : ", ") + std::string("[") + std::to_string(i) + "] " + devs[i].name;
            throw RuntimeError("--device " + spec + ": names " + std::to_string(matches.size()) + " OpenCL devices (" +
                               names + "); give its index or more of its name");
        }
    }
    throw RuntimeError("--device " + spec + ": no such OpenCL device; available: " + device_list_text(devs) +
                       " (or use --backend embree)");
}

}  // namespace

ClDeviceInfo select_cl_device(const std::string& spec) {
    ClDeviceInfo dev = pick_cl_device(spec);
    check_pocl_cache_dir(dev);
    return dev;
}

}  // namespace tessera
