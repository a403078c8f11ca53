#include "backend/backend.h"

#include "util/error.h"

namespace tessera {

BackendKind parse_backend_kind(const std::string& s) {
    if (s == "opencl") return BackendKind::OpenCL;
    if (s == "embree") return BackendKind::Embree;
    throw InputError("--backend " + s + ": expected opencl or embree");
}

std::unique_ptr<Backend> make_backend(const BackendOptions& options, const SceneBuffers& scene,
                                      const EffectPlan& plan) {
    if (options.kind == BackendKind::Embree) return make_embree_backend(scene);
    return make_opencl_backend(scene, plan, options.device);
}

}  // namespace tessera
