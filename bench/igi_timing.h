// Timing IGI-family frames for the benchmarks (igi_bench, ais_bench): one warm-up frame
// (it builds or loads the OpenCL programs), then `frames` timed frames, each with its own
// path block, and the medians of the frame time and of each stage.
#pragma once
#include <algorithm>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "integrators/ais_frame.h"
#include "device/frame.h"
#include "scene/scene.h"

namespace tessera::bench {

inline double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

/// The scenes the seed-style tables report, in the rows of the seed's Tables 5.1-5.3:
/// Cornell, Deskar, Subdivided, Desk, Sibenik, Office, Conference, Shirley6, then the PM
/// versions of Subdivided, Office and Shirley6 (stand-ins, scenes/README.md). Same list as
/// bench/standard_scenes.py, which the Python benchmarks read.
inline std::vector<std::string> standard_scenes() {
    std::vector<std::string> s;
    for (const char* n : {"cornell-box", "deskar", "subdivided", "desk", "sibenik", "office", "conference", "shirley6",
                          "subdivided-fog", "office-fog", "shirley6-fog"})
        s.push_back(std::string(TESSERA_SCENES_DIR) + "/" + n + ".json");
    return s;
}

/// Medians over the timed frames, in seconds; stats of the last frame for the counts.
struct IgiTiming {
    double frame = 0, vpl = 0, surface = 0, media = 0, filter = 0;
    double ais = 0;  ///< AIS: guidance, schedule and the extra sets
    IgiFrameStats last;
};

/// `adaptive`: AIS (AisFrame, mode is.ais_mode) instead of plain IGI. `pass_aovs`
/// (IgiSettings::pass_aovs) false by default, as the viewer showing radiance: a frame
/// resolved on the device reads back its radiance alone; `render` reads back the whole pass
/// for its checkpoint. Frames reconstructed on the host are the same either way.
inline IgiTiming time_igi_frames(Backend& be, const Scene& scene, const SceneBuffers& b, const IgiSettings& is,
                                 int size, int frames, bool adaptive = false, bool pass_aovs = false) {
    IgiSettings shown = is;
    shown.pass_aovs = pass_aovs;
    const std::unique_ptr<IgiFrame> frame_ptr =
        adaptive ? std::make_unique<AisFrame>(be, b, plan_effects(scene), shown)
                 : std::make_unique<IgiFrame>(be, b, plan_effects(scene), shown);
    IgiFrame& igi = *frame_ptr;
    TsFrame f = make_frame(scene.camera, size, size, is.set_shadow_samples, 1, b.light_count);
    f.light_power = b.light_power;
    std::vector<float> out;
    igi.render_pass(f, out);
    std::vector<double> total, vpl, surf, media, filt, ais;
    for (int i = 0; i < frames; ++i) {
        f.pass = static_cast<uint32_t>(i + 1);
        const auto t0 = std::chrono::steady_clock::now();
        igi.render_pass(f, out);
        total.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        vpl.push_back(igi.stats().vpl_seconds);
        surf.push_back(igi.stats().surface_seconds);
        media.push_back(igi.stats().media_seconds);
        filt.push_back(igi.stats().filter_seconds);
        ais.push_back(igi.stats().ais_seconds);
    }
    return {median(total), median(vpl), median(surf), median(media), median(filt), median(ais), igi.stats()};
}

}  // namespace tessera::bench
