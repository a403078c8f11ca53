// What a render's image depends on, apart from its pass count (RunIdentity): a
// checkpoint stores it and --resume checks it (render/checkpoint.h). Apart from the
// checkpoint reader, so that reading a checkpoint needs neither a scene nor the methods.
#pragma once
#include <cstdint>
#include <string>

#include "backend/backend.h"
#include "render/settings.h"
#include "scene/scene.h"

namespace tessera {

/// Everything that determines the image of a render, apart from the pass count.
struct RunIdentity {
    std::string scene_path;
    uint64_t scene_file_hash = 0;
    uint64_t scene_data_hash = 0;
    std::string method;
    uint32_t seed = 0;
    uint32_t shadow_samples = 0;
    uint32_t max_depth = 0;
    uint32_t max_scatter = 0;
    int32_t width = 0, height = 0;
    std::string backend;
    /// Every other setting the method reads, resolved (ic's path subsets from --spp and
    /// the image size), as "--option value" pairs in the order of render_parameters(),
    /// then --components for the igi family: the text names the setting that differs.
    std::string method_settings;

    bool operator==(const RunIdentity&) const = default;
};

/// The identity of rendering `scene` (its `source` file is read and hashed; throws
/// InputError naming it if it cannot be read) with `settings` at width × height.
RunIdentity make_run_identity(const Scene& scene, const RenderSettings& settings, int width, int height,
                              BackendKind backend);

}  // namespace tessera
