// Helpers shared by rendering tests: run a backend on a scene, compare images.
#pragma once
#include <cmath>
#include <memory>
#include <vector>

#include "backend/backend.h"
#include "image/image_io.h"
#include "device/effect_plan.h"
#include "render/renderer.h"
#include "device/scene_buffers.h"
#include "scene/scene.h"

namespace tessera::test {

inline Image render_with(BackendKind kind, const Scene& scene, const RenderSettings& settings) {
    SceneBuffers buffers = make_scene_buffers(scene);
    auto backend = make_backend(BackendOptions{kind, ""}, buffers, plan_effects(scene));
    return render_frame(*backend, scene, buffers, settings);
}

/// Mean over pixels of (a - b)² / (b² + 0.01), over R, G, B: the relative MSE of
/// Rousselle et al. 2011 (the 0.01 keeps dark pixels from dominating).
inline double rel_mse(const Image& a, const Image& b) {
    double sum = 0.0;
    size_t n = 0;
    for (const char* c : {"R", "G", "B"}) {
        const auto& x = a.find(c)->data;
        const auto& y = b.find(c)->data;
        for (size_t i = 0; i < x.size(); ++i, ++n) {
            double d = double(x[i]) - y[i];
            sum += d * d / (double(y[i]) * y[i] + 0.01);
        }
    }
    return sum / n;
}

inline bool all_finite(const Image& img) {
    for (const auto& c : img.channels) {
        if (c.name == "Z") continue;  // +inf marks a miss by design
        for (float v : c.data)
            if (!std::isfinite(v)) return false;
    }
    return true;
}

inline double channel_mean(const Image& img, const char* name) {
    double s = 0.0;
    for (float v : img.find(name)->data) s += v;
    return s / img.find(name)->data.size();
}

}  // namespace tessera::test
