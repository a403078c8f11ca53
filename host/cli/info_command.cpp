// `tessera info [SCENE]`: what a scene contains and which effects it calls for.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "cli/commands.h"
#include "cli/option_checks.h"
#include "kernels/shared/layout_scene.h"
#include "device/coincident_emitters.h"
#include "device/effect_plan.h"
#include "device/scene_buffers.h"
#include "scene/loader.h"

namespace tessera::cli {
namespace fs = std::filesystem;

namespace {
struct InfoArgs {
    std::string scene;
    std::string data_dir;
};

void run_info(const InfoArgs& a, const CLI::App& cmd) {
    reject_empty_values(cmd);
    check_data_dir(a.data_dir);
    const fs::path path = a.scene.empty() ? default_scene_path() : fs::path(a.scene);
    Scene s = load_scene(path, make_data_path(a.data_dir.empty() ? std::nullopt
                                                                 : std::optional<fs::path>(a.data_dir)));
    // Searched all the same (a scene may not need it; scripts/reference makes it later),
    // but said here, where a user looks: a missing file's error lists it among the
    // directories tried. (--data-dir of the same is an error.)
    if (const char* env = std::getenv("TESSERA_DATA"); env && *env) {
        std::error_code ec;
        if (!fs::is_directory(env, ec)) std::fprintf(stderr, "tessera: note: TESSERA_DATA=%s is not a directory\n", env);
    }
    print_scene_notes(s.notes);
    SceneBuffers b = make_scene_buffers(s);
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const auto& p : s.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    double light_area = 0.0;
    for (uint32_t i = 0; i < b.light_count; ++i) light_area += b.lights[i * TS_LIGHT_FLOATS + TS_LIGHT_AREA];
    const EffectPlan plan = plan_effects_over_animation(s);
    std::printf("scene:      %s (%s)\n", s.name.c_str(), s.source.c_str());
    std::printf("triangles:  %zu\n", s.triangle_count());
    std::printf("lights:     %u emissive triangles, %.4g scene units^2\n", b.light_count, light_area);
    if (b.separated_emitters > 0)
        std::printf("            %u of them lay on another surface: moved %g ulps in front of it (docs/ray-tracing.md §4)\n",
                    b.separated_emitters, double(kCoincidentEmitterUlps));
    if (b.stacked_emitters > 0) std::printf("            %s\n", stacked_emitters_text(b.stacked_emitters).c_str());
    size_t mirrors = 0, dielectrics = 0;
    for (const Material& m : s.materials) {
        mirrors += m.is_mirror();
        dielectrics += m.is_dielectric();
    }
    std::printf("materials:  %zu", s.materials.size());
    if (mirrors + dielectrics > 0) std::printf(" (%zu mirror, %zu dielectric)", mirrors, dielectrics);
    std::printf(", textures: %zu\n", s.textures.size());
    std::printf("bounds:     (%g, %g, %g) .. (%g, %g, %g)\n", lo.x, lo.y, lo.z, hi.x, hi.y, hi.z);
    std::printf("camera:     %dx%d, vfov %g, at (%g, %g, %g)\n", s.camera.width, s.camera.height,
                s.camera.vfov_deg, s.camera.position.x, s.camera.position.y, s.camera.position.z);
    size_t json_lights = 0;
    for (const SceneObject& o : s.objects) json_lights += o.json_light;
    std::printf("objects:    %zu", s.objects.size() - json_lights);
    if (json_lights > 0) std::printf(" and %zu quad light%s of the scene file", json_lights, json_lights == 1 ? "" : "s");
    std::printf("\n");
    if (s.animation.animated())
        std::printf("animation:  %d frames; tracks: %zu objects, %zu materials, camera %s\n",
                    s.animation.frame_count, s.animation.objects.size(), s.animation.materials.size(),
                    s.animation.camera.empty() ? "fixed" : "keyed");
    std::printf("effects:\n");
    for (const auto& line : plan.describe()) std::printf("  %s\n", line.c_str());
    std::string defs;
    for (const auto& d : plan.cl_defines()) defs += " " + d;
    // The programs each method builds (host/device/kernel_table.h; trace.cl: the batches of
    // rays the host traces), all with the same options: those the scene decides here, and
    // those of the device and the environment (host/opencl/program_cache.h).
    std::printf("OpenCL programs, built with -cl-std=CL1.2%s (and the device's division option, a GPU's "
                "traversal define, $TESSERA_CL_OPTIONS):\n", defs.c_str());
    std::printf("  direct: direct.cl; pt: pt.cl; igi, ais, ais-max: igi.cl, trace.cl; ic, tic: igi.cl, ic.cl, "
                "trace.cl\n");
}
}  // namespace

void add_info_command(CLI::App& app) {
    auto args = std::make_shared<InfoArgs>();
    CLI::App* cmd = app.add_subcommand("info", "Describe a scene and the effects it calls for");
    cmd->add_option("scene", args->scene, "Scene file (.json); default " + default_scene_path().string());
    cmd->add_option("--data-dir", args->data_dir, "Directory searched for scene data");
    cmd->callback([args, cmd] { run_info(*args, *cmd); });
}

}  // namespace tessera::cli
