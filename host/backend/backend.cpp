#include "backend/backend.h"

#include <cstdlib>
#include <stdexcept>

#include "util/error.h"

namespace tessera {

BackendKind parse_backend_kind(const std::string& s) {
    if (s == "opencl") return BackendKind::OpenCL;
    if (s == "embree") return BackendKind::Embree;
    throw InputError("--backend " + s + ": expected opencl or embree");
}

void Backend::launch(KernelId k, const TsFrame& frame, std::vector<float>& out) {
    const KernelInfo& info = kernel_info(k);
    if (info.item_words != 0) throw std::logic_error(std::string(info.name) + " is an item kernel (launch_items)");
    const size_t pixels = size_t(frame.width) * frame.height;
    out.resize(pixels * static_cast<size_t>(info.out_floats));
    ++dispatches_[static_cast<int>(k)];
    run_kernel(k, frame, pixels, {}, out);
}

void Backend::launch_items(KernelId k, const TsFrame& frame, const std::vector<uint32_t>& items,
                           std::vector<float>& out) {
    const KernelInfo& info = kernel_info(k);
    if (info.item_words == 0) throw std::logic_error(std::string(info.name) + " is a pixel kernel (launch)");
    const size_t count = items.size() / static_cast<size_t>(info.item_words);
    out.resize(count * static_cast<size_t>(info.out_floats));
    if (count == 0) return;
    ++dispatches_[static_cast<int>(k)];
    run_kernel(k, frame, count, items, out);
}

void Backend::set_input(KernelInput in, const std::vector<float>& data) {
    if (input_info(in).is_uint) throw std::logic_error(std::string(input_info(in).name) + " input holds uints");
    store_input(in, data);
}

void Backend::set_input(KernelInput in, const std::vector<uint32_t>& data) {
    if (!input_info(in).is_uint) throw std::logic_error(std::string(input_info(in).name) + " input holds floats");
    store_input(in, data);
}

std::unique_ptr<Backend> make_backend(const BackendOptions& options, const SceneBuffers& scene,
                                      const EffectPlan& plan) {
    if (options.kind == BackendKind::Embree) {
        // TESSERA_EMBREE_PACKETS=0 turns packets off for a whole run (benchmarks compare
        // the two tracers with one binary; the images are the same either way).
        const char* env = std::getenv("TESSERA_EMBREE_PACKETS");
        const bool packets = options.embree_packets && !(env && std::string(env) == "0");
        return make_embree_backend(scene, packets);
    }
    // TESSERA_CL_PACKETS=0 likewise turns the OpenCL CPU packet kernels off.
    const char* env = std::getenv("TESSERA_CL_PACKETS");
    const bool packets = options.cl_packets && !(env && std::string(env) == "0");
    return make_opencl_backend(scene, plan, options.device, packets);
}

}  // namespace tessera
