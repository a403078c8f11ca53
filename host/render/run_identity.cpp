#include "render/run_identity.h"

#include <fstream>
#include <iterator>
#include <system_error>
#include <vector>

#include "render/checkpoint.h"
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
        const float f[7] = {m.albedo.x, m.albedo.y, m.albedo.z, m.emission.x, m.emission.y, m.emission.z, m.ior};
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

}  // namespace

RunIdentity make_run_identity(const Scene& scene, const RenderSettings& settings, int width, int height,
                              BackendKind backend) {
    RunIdentity id;
    if (!scene.source.empty()) {
        std::error_code ec;
        fs::path p = fs::weakly_canonical(fs::absolute(scene.source), ec);
        id.scene_path = (ec ? fs::absolute(scene.source).lexically_normal() : p).string();
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
    return id;
}

}  // namespace tessera
