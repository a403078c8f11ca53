#include "backend/backend.h"

#include <chrono>
#include <cerrno>
#include <cstdlib>
#include <stdexcept>

#include "kernels/shared/layout_igi.h"
#include "util/error.h"

namespace tessera {

namespace {

const char* env_value(const char* name) {
    const char* v = std::getenv(name);
    return v && *v ? v : nullptr;
}

// A non-negative number up to `max` from environment variable `name`; throws InputError
// naming the variable and its value otherwise.
double parse_env_number(const char* name, const char* value, double max) {
    char* end = nullptr;
    const double v = std::strtod(value, &end);
    if (end == value || *end != '\0' || !(v >= 0.0 && v <= max))
        throw InputError(std::string(name) + "=" + value + ": expected a number from 0 to " +
                         std::to_string(static_cast<long long>(max)));
    return v;
}

// An OpenCL error code from environment variable `name`: a whole number from -9999 to 0
// (the codes are negative; 0: none); anything else throws InputError naming the variable
// and its value.
int32_t parse_env_cl_error(const char* name, const char* value) {
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(value, &end, 10);
    if (end == value || *end != '\0' || errno != 0 || v < -9999 || v > 0)
        throw InputError(std::string(name) + "=" + value + ": expected an OpenCL error code, a whole number from -9999 to 0");
    return static_cast<int32_t>(v);
}

// An on/off switch from environment variable `name`: unset or empty: `otherwise`; "0" or
// "1"; anything else throws InputError naming the variable and its value.
bool env_switch(const char* name, bool otherwise) {
    const char* v = env_value(name);
    if (!v) return otherwise;
    if (std::string(v) == "0" || std::string(v) == "1") return std::string(v) == "1";
    throw InputError(std::string(name) + "=" + v + ": expected 0 or 1");
}

}  // namespace

BackendKind parse_backend_kind(const std::string& s) {
    if (s == "opencl") return BackendKind::OpenCL;
    if (s == "embree") return BackendKind::Embree;
    throw InputError("--backend " + s + ": expected opencl or embree");
}

template <class F>
void Backend::dispatch_timed(KernelId k, size_t count, F&& run) {
    const int i = static_cast<int>(k);
    wall_seconds_[i] = 0.0;
    if (count == 0) return forget_launch(k);
    ++dispatches_[i];
    const auto t0 = std::chrono::steady_clock::now();
    run();
    wall_seconds_[i] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void Backend::launch(KernelId k, const TsFrame& frame, std::vector<float>& out) {
    const KernelInfo& info = kernel_info(k);
    if (info.item_words != 0) throw std::logic_error(std::string(info.name) + " is an item kernel (launch_items)");
    const size_t pixels = size_t(frame.width) * frame.height;
    out.resize(pixels * static_cast<size_t>(info.out_floats));
    dispatch_timed(k, pixels, [&] { run_kernel(k, frame, pixels, {}, out); });
}

void Backend::launch_into(KernelId k, const TsFrame& frame, KernelInput in) {
    const KernelInfo& info = kernel_info(k);
    if (info.item_words != 0) throw std::logic_error(std::string(info.name) + " is an item kernel (launch_items)");
    if (input_info(in).is_uint) throw std::logic_error(std::string(input_info(in).name) + " input holds uints");
    const size_t pixels = size_t(frame.width) * frame.height;
    dispatch_timed(k, pixels, [&] { run_kernel_into(k, frame, pixels, {}, in); });
}

void Backend::launch_items_into(KernelId k, const TsFrame& frame, const std::vector<uint32_t>& items, KernelInput in) {
    const KernelInfo& info = kernel_info(k);
    if (info.item_words == 0) throw std::logic_error(std::string(info.name) + " is a pixel kernel (launch_into)");
    if (input_info(in).is_uint) throw std::logic_error(std::string(input_info(in).name) + " input holds uints");
    const size_t count = items.size() / static_cast<size_t>(info.item_words);
    if (count == 0) store_input(in, std::vector<float>(1, 0.0f));
    dispatch_timed(k, count, [&] { run_kernel_into(k, frame, count, items, in); });
}

void Backend::launch_count(KernelId k, const TsFrame& frame, size_t count, std::vector<float>& out) {
    const KernelInfo& info = kernel_info(k);
    if (info.item_words == 0) throw std::logic_error(std::string(info.name) + " is a pixel kernel (launch)");
    out.resize(count * static_cast<size_t>(info.out_floats));
    dispatch_timed(k, count, [&] { run_kernel(k, frame, count, {}, out); });
}

void Backend::launch_count_into(KernelId k, const TsFrame& frame, size_t count, KernelInput in) {
    const KernelInfo& info = kernel_info(k);
    if (info.item_words == 0) throw std::logic_error(std::string(info.name) + " is a pixel kernel (launch_into)");
    if (input_info(in).is_uint) throw std::logic_error(std::string(input_info(in).name) + " input holds uints");
    if (count == 0) store_input(in, std::vector<float>(1, 0.0f));
    dispatch_timed(k, count, [&] { run_kernel_into(k, frame, count, {}, in); });
}

void Backend::read_input(KernelInput in, std::vector<float>& out) {
    if (input_info(in).is_uint) throw std::logic_error(std::string(input_info(in).name) + " input holds uints");
    fetch_input(in, out);
}

void Backend::launch_items(KernelId k, const TsFrame& frame, const std::vector<uint32_t>& items,
                           std::vector<float>& out) {
    const KernelInfo& info = kernel_info(k);
    if (info.item_words == 0) throw std::logic_error(std::string(info.name) + " is a pixel kernel (launch)");
    const size_t count = items.size() / static_cast<size_t>(info.item_words);
    out.resize(count * static_cast<size_t>(info.out_floats));
    dispatch_timed(k, count, [&] { run_kernel(k, frame, count, items, out); });
}

void Backend::set_input(KernelInput in, const std::vector<float>& data) {
    if (input_info(in).is_uint) throw std::logic_error(std::string(input_info(in).name) + " input holds uints");
    store_input(in, data);
}

void Backend::set_input(KernelInput in, const std::vector<uint32_t>& data) {
    if (!input_info(in).is_uint) throw std::logic_error(std::string(input_info(in).name) + " input holds floats");
    unchanged_[static_cast<int>(in)].reset();
    store_input(in, data);
}

void Backend::set_input_if_changed(KernelInput in, const std::vector<uint32_t>& data) {
    std::optional<std::vector<uint32_t>>& last = unchanged_[static_cast<int>(in)];
    if (last && *last == data) return;
    set_input(in, data);  // a uint input (or it throws); only uint inputs are written here
    last = data;
    ++changed_input_stores_;
}

void Backend::store_placeholder_inputs() {
    for (int i = 0; i < kKernelInputCount; ++i) {
        const KernelInput in = static_cast<KernelInput>(i);
        if (input_info(in).is_uint)
            store_input(in, std::vector<uint32_t>(1, 0u));
        else
            store_input(in, std::vector<float>(1, 0.0f));
    }
    store_input(KernelInput::Vpls, std::vector<float>(TS_VPL_FLOATS, 0.0f));
    store_input(KernelInput::VplSetStart, std::vector<uint32_t>(2, 0u));
}

void give_scene(std::unique_ptr<Backend>& backend, const BackendOptions& options, const SceneBuffers& scene,
                const EffectPlan& plan) {
    if (backend)
        backend->set_scene(scene, plan);
    else
        backend = make_backend(options, scene, plan);
}

std::unique_ptr<Backend> make_backend(const BackendOptions& options, const SceneBuffers& scene,
                                      const EffectPlan& plan) {
    if (options.kind == BackendKind::Embree) {
        // TESSERA_EMBREE_PACKETS=0 turns packets off for a whole run (benchmarks compare
        // the two tracers with one binary; the images are the same either way).
        return make_embree_backend(scene, options.embree_packets && env_switch("TESSERA_EMBREE_PACKETS", true));
    }
    // TESSERA_CL_PACKETS=0 likewise turns the OpenCL CPU packet kernels off;
    // TESSERA_CL_GPU=1 runs the GPU variant on any device, TESSERA_CL_GPU=0 on none;
    // TESSERA_CL_LIGHT_PATHS=1 / 0 the light-path kernel; TESSERA_CL_LAUNCH_MS and
    // TESSERA_CL_TILE_GROUPS set the launch tiling, TESSERA_CL_IMPORTANCE_CHUNK the view
    // importance's chunks, TESSERA_CL_LIGHT_PATH_GATHER=1 / 0 the light paths' gathered
    // read-back (BackendOptions).
    BackendOptions o = options;
    o.cl_packets = options.cl_packets && env_switch("TESSERA_CL_PACKETS", true);
    if (env_value("TESSERA_CL_GPU")) o.cl_gpu_variant = env_switch("TESSERA_CL_GPU", false);
    if (env_value("TESSERA_CL_LIGHT_PATHS")) o.cl_light_path_kernel = env_switch("TESSERA_CL_LIGHT_PATHS", false);
    if (env_value("TESSERA_CL_LIGHT_PATH_GATHER"))
        o.cl_light_path_gather = env_switch("TESSERA_CL_LIGHT_PATH_GATHER", false);
    if (const char* ms = env_value("TESSERA_CL_LAUNCH_MS")) o.cl_launch_ms = parse_env_number("TESSERA_CL_LAUNCH_MS", ms, 1e6);
    if (const char* g = env_value("TESSERA_CL_TILE_GROUPS")) {
        const double n = parse_env_number("TESSERA_CL_TILE_GROUPS", g, 1e9);
        if (n != static_cast<double>(static_cast<uint32_t>(n)))
            throw InputError(std::string("TESSERA_CL_TILE_GROUPS=") + g + ": expected a whole number of work-groups");
        o.cl_tile_groups = static_cast<uint32_t>(n);
    }
    if (const char* c = env_value("TESSERA_CL_IMPORTANCE_CHUNK")) {
        const double n = parse_env_number("TESSERA_CL_IMPORTANCE_CHUNK", c, double(TS_VI_MAX_CHUNK));
        if (n != static_cast<double>(static_cast<uint32_t>(n)))
            throw InputError(std::string("TESSERA_CL_IMPORTANCE_CHUNK=") + c + ": expected a whole number of VPLs");
        o.cl_importance_chunk = static_cast<uint32_t>(n);
    }
    if (const char* c = env_value("TESSERA_CL_FAIL_LAUNCH")) o.cl_fail_launch = parse_env_cl_error("TESSERA_CL_FAIL_LAUNCH", c);
    return make_opencl_backend(scene, plan, o);
}

}  // namespace tessera
