// Helpers shared by rendering tests: run a backend on a scene, compare images.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "backend/backend.h"
#include "image/image_io.h"
#include "device/effect_plan.h"
#include "render/renderer.h"
#include "device/scene_buffers.h"
#include "scene/loader.h"
#include "scene/scene.h"

namespace tessera::test {

/// The default scene (scenes/cornell-box.json), loaded without a data directory.
inline Scene cornell_box() { return load_scene(default_scene_path(), make_data_path(std::nullopt)); }

/// The shipped scene `file` of scenes/ (e.g. "cornell-box-animated.json"), without a data directory.
inline Scene shipped_scene(const char* file) {
    return load_scene(default_scene_path().parent_path() / file, make_data_path(std::nullopt));
}

/// OpenCL on the default device, one ray per work item (no 16-ray packets): with
/// `gpu_variant` the GPU variant (short stack, frames resolved on the device), forced on
/// whatever device this is, else its per-ray CPU twin, which reconstructs on the host.
/// `light_path_kernel` false: both trace the light paths on the host, so their VPLs are
/// the same bits (BackendOptions::cl_light_path_kernel).
inline BackendOptions opencl_per_ray(bool gpu_variant, bool light_path_kernel = true) {
    BackendOptions o{BackendKind::OpenCL, ""};
    o.cl_packets = false;
    o.cl_gpu_variant = gpu_variant;
    o.cl_light_path_kernel = light_path_kernel;
    return o;
}

inline Image render_with(BackendKind kind, const Scene& scene, const RenderSettings& settings) {
    SceneBuffers buffers = make_scene_buffers(scene);
    auto backend = make_backend(BackendOptions{kind, ""}, buffers, plan_effects(scene));
    return render_frame(*backend, scene, buffers, settings);
}

/// Sum of R, G and B over the image (radiance × pixels): what a clamp removed or returned
/// compares as a ratio of two sums.
inline double image_sum(const Image& img) {
    double sum = 0.0;
    for (const char* c : {"R", "G", "B"})
        for (float v : img.find(c)->data) sum += v;
    return sum;
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

/// Pixels at least one pixel away from any pixel brighter than `bright` (R+G+B) in `ref`,
/// the emitter: there a few jittered camera samples decide how much of the light a pixel
/// covers, noise that says nothing about the lighting. true = keep, row-major.
inline std::vector<bool> away_from_emitter(const Image& ref, float bright = 3.0f) {
    const int w = ref.width, h = ref.height;
    const auto &r = ref.find("R")->data, &g = ref.find("G")->data, &b = ref.find("B")->data;
    std::vector<bool> keep(size_t(w) * h, true);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * w + x;
            if (!(r[i] + g[i] + b[i] > bright)) continue;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    if (x + dx >= 0 && x + dx < w && y + dy >= 0 && y + dy < h) keep[size_t(y + dy) * w + x + dx] = false;
        }
    return keep;
}

/// rel_mse over the pixels `keep` marks.
inline double rel_mse_where(const Image& a, const Image& b, const std::vector<bool>& keep) {
    double sum = 0.0;
    size_t n = 0;
    for (const char* c : {"R", "G", "B"}) {
        const auto& x = a.find(c)->data;
        const auto& y = b.find(c)->data;
        for (size_t i = 0; i < x.size(); ++i) {
            if (!keep[i]) continue;
            const double d = double(x[i]) - y[i];
            sum += d * d / (double(y[i]) * y[i] + 0.01);
            ++n;
        }
    }
    return sum / n;
}

/// Expects a and b to hold the same channels with bit-identical data, and not to be
/// black (a black pair would make the comparison vacuous): the packet tracers'
/// images against the single-ray tracers' (tests/backend/*_packets_test.cpp).
inline void expect_images_identical(const Image& a, const Image& b) {
    ASSERT_EQ(a.channels.size(), b.channels.size());
    double sum = 0.0;
    for (size_t c = 0; c < a.channels.size(); ++c) {
        EXPECT_EQ(a.channels[c].name, b.channels[c].name);
        EXPECT_TRUE(a.channels[c].data == b.channels[c].data) << "channel " << a.channels[c].name;
        for (float v : a.channels[c].data) sum += std::isfinite(v) ? v : 0.0f;
    }
    EXPECT_GT(sum, 0.0) << "a black image would make the comparison vacuous";
}

/// The packet image tests' settings for `m` (igi, ais or ais-max): 37×29, not a multiple
/// of the tile (3) nor of the 4×4 packet block, so packets with idle lanes and sets of
/// unequal size are covered; 2 spp, 8 VPL paths per set.
inline RenderSettings packet_test_settings(Method m) {
    RenderSettings rs;
    rs.method = m;
    rs.width = 37;
    rs.height = 29;
    rs.spp = 2;
    rs.igi.tile = 3;
    rs.igi.paths_per_set = 8;
    return rs;
}

/// A gtest parameter name for a method: "igi", "ais", "AisMax".
inline std::string method_param_name(Method m) {
    return std::string(method_name(m)) == "ais-max" ? std::string("AisMax") : std::string(method_name(m));
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

/// Renders `scene` with `rs` on OpenCL and on Embree (same seed) and on Embree with seed
/// + 1000, and expects the two backends to agree: their relMSE under 2% of the seed-to-seed
/// relMSE (the noise), and at most 1 in 200 pixel channels differing by more than 1e-3
/// relative, or one filtered ray's worth where that is more (unless count_differing_pixels
/// is false). Same seed means the same random numbers (counter-based RNG) through the same
/// shading source, so only traversal rounding may differ; tests/render/backend_agreement_test.cpp
/// states the reasoning.
inline void expect_backends_agree(const Scene& scene, RenderSettings rs, bool count_differing_pixels = true) {
    Image cl = render_with(BackendKind::OpenCL, scene, rs);
    Image em = render_with(BackendKind::Embree, scene, rs);
    rs.seed += 1000;
    Image em2 = render_with(BackendKind::Embree, scene, rs);
    ASSERT_TRUE(all_finite(cl));
    ASSERT_TRUE(all_finite(em));
    const double noise = rel_mse(em2, em);
    const double diff = rel_mse(cl, em);
    std::printf("  %s: relMSE OpenCL vs Embree (same seed) %.3g; seed vs seed %.3g\n", scene.name.c_str(), diff,
                noise);
    ASSERT_GT(noise, 0.0);
    EXPECT_LT(diff, 0.02 * noise) << "backend relMSE " << diff << " vs seed-to-seed relMSE " << noise;
    // relMSE is dominated by a few edge pixels (an emitter next to black), so also
    // bound how many pixels differ at all: the same samples must give the same value
    // except where a tie or rounding sends one camera or shadow ray elsewhere.
    size_t differ = 0, total = 0;
    for (const char* c : {"R", "G", "B"}) {
        const auto& a = cl.find(c)->data;
        const auto& b = em.find(c)->data;
        for (size_t i = 0; i < a.size(); ++i, ++total)
            differ += std::abs(a[i] - b[i]) > 1e-3f * (std::abs(b[i]) + 0.01f);
    }
    std::printf("  %s: %zu of %zu pixel channels differ by more than 1e-3\n", scene.name.c_str(), differ, total);
    // One ray that rounding sends elsewhere changes one pixel, and the discontinuity
    // filter spreads that pixel over its tile² window: 3·tile² channels. At 32² a
    // 1/200 share (15 channels) is less than one such ray, so allow one.
    const size_t one_ray = 3u * rs.igi.tile * rs.igi.tile;
    if (count_differing_pixels) {
        EXPECT_LE(differ, std::max(total / 200, one_ray));
    }
}

}  // namespace tessera::test
