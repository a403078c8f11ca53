#include "render/run_identity.h"

#include <cstdio>
#include <fstream>
#include <iterator>
#include <set>
#include <utility>
#include <system_error>
#include <vector>

#include "integrators/method.h"
#include "kernels/shared/layout_igi.h"
#include "render/checkpoint.h"
#include "render/parameters.h"
#include "render/renderer.h"
#include "scene/loader.h"
#include "util/error.h"

namespace tessera {
namespace fs = std::filesystem;
namespace {

template <class T> uint64_t hash_vec(const std::vector<T>& v, uint64_t h) {
    return fnv1a64(v.data(), v.size() * sizeof(T), h);
}

uint64_t scene_data_hash(const Scene& s) {
    uint64_t h = fnv1a64(nullptr, 0);
    h = hash_vec(s.positions, h);
    h = hash_vec(s.normals, h);
    h = hash_vec(s.uvs, h);
    h = hash_vec(s.material, h);
    for (const Material& m : s.materials) {
        // emission_max: the light list and its pick weights (scene_buffers.h); specular: a
        // mirror's or a dielectric's reflectance (MTL Ks).
        const float f[13] = {m.albedo.x,       m.albedo.y,       m.albedo.z,       m.emission.x, m.emission.y,
                             m.emission.z,     m.ior,            m.emission_max.x, m.emission_max.y,
                             m.emission_max.z, m.specular.x,     m.specular.y,     m.specular.z};
        const int32_t i[2] = {m.texture, m.illum};
        h = fnv1a64(f, sizeof f, h);
        h = fnv1a64(i, sizeof i, h);
    }
    for (const Texture& t : s.textures) {
        const int32_t wh[2] = {t.width, t.height};
        h = fnv1a64(wh, sizeof wh, h);
        h = hash_vec(t.rgba8, h);
    }
    const Camera& c = s.camera;
    const float cam[10] = {c.position.x, c.position.y, c.position.z, c.look_at.x, c.look_at.y,
                           c.look_at.z,  c.up.x,       c.up.y,       c.up.z,        c.vfov_deg};
    return fnv1a64(cam, sizeof cam, h);
}

// The settings of RunIdentity's own fields, and those that do not change what `method`
// accumulates: the pass count (--spp may be raised on resume), the checkpoint interval,
// --aov but for the igi family (direct's and pt's albedo, normal and depth are in every
// pass; the igi family's per-component channels are summed only with --aov), and
// --no-mipmaps for pt, which always reads the finest level.
bool identity_field_or_no_effect(const std::string& option, Method method) {
    static const std::set<std::string> kSkip = {"--spp",  "--shadow-samples", "--width",       "--height",
                                                "--seed", "--max-depth",      "--max-scatter", "--checkpoint-interval"};
    if (option == "--aov") return !igi_family(method);
    if (option == "--no-mipmaps") return method == Method::PathTrace;
    return kSkip.count(option) > 0;
}

std::string method_settings_text(const RenderSettings& settings, int width, int height) {
    RenderSettings resolved = settings;
    resolve_ic_subsets(resolved, width, height);
    std::string text;
    for (const Parameter& p : render_parameters()) {
        if (identity_field_or_no_effect(p.option, settings.method) || !parameter_applies(p, settings.method)) continue;
        const double v = parameter_value(p, resolved);
        char value[32];
        if (*p.value_name == '\0')  // a flag: whether it was given
            std::snprintf(value, sizeof value, "%s", (p.negated ? v == 0 : v != 0) ? "given" : "absent");
        else
            std::snprintf(value, sizeof value, "%.9g", v);
        text += (text.empty() ? "" : " ") + std::string(p.option) + " " + value;
    }
    if (igi_family(settings.method)) {
        // Edge samples are AIS's (--ais-edge-samples); the other methods drop the bit.
        const bool edges = parameter_applies(*find_parameter("--ais-edge-samples"), settings.method);
        text += " --components " + components_text(settings.igi.components & (edges ? ~0u : ~TS_COMPONENT_EDGE));
    }
    return text;
}

}  // namespace

RunIdentity make_run_identity(const Scene& scene, const RenderSettings& settings, int width, int height,
                              BackendKind backend) {
    RunIdentity id;
    if (!scene.source.empty()) {
        id.scene_path = same_file(scene.source).string();
        std::ifstream in(scene.source, std::ios::binary);
        std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (!in.eof() && !in) throw InputError(scene.source.string() + ": cannot read scene file");
        id.scene_file_hash = fnv1a64(bytes.data(), bytes.size());
    }
    id.scene_data_hash = scene_data_hash(scene);
    id.method = method_name(settings.method);
    id.seed = settings.seed;
    id.shadow_samples = settings.shadow_samples;
    id.max_depth = settings.max_depth;
    id.max_scatter = settings.max_scatter;
    id.width = width;
    id.height = height;
    id.backend = backend == BackendKind::OpenCL ? "opencl" : "embree";
    id.method_settings = method_settings_text(settings, width, height);
    return id;
}

}  // namespace tessera
