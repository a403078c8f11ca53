// libFuzzer target for the scene loader (tessera::load_scene: JSON, OBJ, MTL, PNG).
//
// Input format (so that seeds stay readable text): up to four parts separated by a line
// "@@@@", written to a fresh temporary directory as
//   scene.json   mesh.obj   mesh.mtl   tex.png
// (a part that is absent is not written, which exercises the missing-file paths), then
// load_scene(dir/scene.json) with an empty data path, so nothing outside that directory
// is found by relative path.
//
// Expected outcomes: a Scene, or tessera::InputError. A loaded Scene must keep the
// promises of scene/scene.h (finite positions, unit normals, indices in range, albedo and
// specular in [0, 1], finite non-negative emission, a usable camera); a broken promise
// aborts, as does any other exception, a crash, a leak or undefined behaviour (the target
// is built with -fsanitize=fuzzer,address,undefined).
//
// Build: cmake -DTESSERA_FUZZ=ON with clang (scripts/fuzz does it); see tests/README.md.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_scratch_dir.h"
#include "scene/loader.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace {

const fs::path& scratch_dir() { return tessera::fuzz::scratch_dir(""); }

void write_file(const fs::path& p, std::string_view bytes) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

[[noreturn]] void broken(const char* what) {
    std::fprintf(stderr, "scene_loader_fuzzer: loaded scene breaks a promise of scene.h: %s\n", what);
    std::abort();
}

bool finite3(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool in01(glm::vec3 v) {
    for (int i = 0; i < 3; ++i)
        if (!(v[i] >= 0.0f && v[i] <= 1.0f)) return false;
    return true;
}

void check_scene(const tessera::Scene& s) {
    const size_t n = s.triangle_count();
    if (s.positions.size() != 3 * n || s.normals.size() != 3 * n || s.uvs.size() != 3 * n)
        broken("per-vertex arrays do not match the triangle count");
    for (const auto& p : s.positions)
        if (!finite3(p)) broken("a position is not finite");
    for (const auto& nm : s.normals) {
        if (!finite3(nm)) broken("a normal is not finite");
        if (std::fabs(glm::length(nm) - 1.0f) > 1e-3f) broken("a normal is not unit length");
    }
    for (const auto& uv : s.uvs)
        if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) broken("a texture coordinate is not finite");
    for (uint32_t m : s.material)
        if (m >= s.materials.size()) broken("a material index is out of range");
    for (const auto& m : s.materials) {
        if (!in01(m.albedo)) broken("an albedo is outside [0, 1]");
        if (!in01(m.specular)) broken("a specular reflectance is outside [0, 1]");
        if (!finite3(m.emission) || m.emission.x < 0 || m.emission.y < 0 || m.emission.z < 0)
            broken("an emission is negative or not finite");
        if (m.texture >= static_cast<int>(s.textures.size())) broken("a texture index is out of range");
        if (!(std::isfinite(m.ior) && m.ior >= 0.0f)) broken("an Ni is negative or not finite");
        if (!(m.ior > 0.0f) && m.illum == 7) broken("a dielectric's Ni is not positive");
        if (m.illum < 0 || m.illum > 10) broken("an illum is outside 0..10");
    }
    for (const auto& t : s.textures)
        if (t.width <= 0 || t.height <= 0 || t.rgba8.size() != size_t(t.width) * size_t(t.height))
            broken("a texture's size does not match its texels");
    const auto& c = s.camera;
    if (!finite3(c.position) || !finite3(c.look_at) || !finite3(c.up)) broken("the camera is not finite");
    if (!(c.vfov_deg > 0.0f && c.vfov_deg < 180.0f) || c.width <= 0 || c.height <= 0)
        broken("the camera's field of view or resolution is out of range");
    if (s.has_medium) {
        const auto& m = s.medium;
        if (!finite3(m.sigma_a) || !finite3(m.sigma_s) || !(m.g > -1.0f && m.g < 1.0f))
            broken("the medium is not finite or g is outside (-1, 1)");
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view input(reinterpret_cast<const char*>(data), size);
    static const char* const names[] = {"scene.json", "mesh.obj", "mesh.mtl", "tex.png"};
    const fs::path& dir = scratch_dir();
    for (const char* name : names) fs::remove(dir / name);

    constexpr std::string_view sep = "\n@@@@\n";
    size_t start = 0;
    for (const char* name : names) {
        if (start > input.size()) break;
        const size_t end = input.find(sep, start);
        const std::string_view part = input.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start);
        write_file(dir / name, part);
        if (end == std::string_view::npos) break;
        start = end + sep.size();
    }

    try {
        const tessera::Scene s = tessera::load_scene(dir / "scene.json", tessera::DataPath{});
        check_scene(s);
    } catch (const tessera::InputError&) {
        // bad input, reported as such: the expected outcome
    }
    // Any other exception escapes, and libFuzzer reports it as a crash.
    return 0;
}
