#include "gi/igi_frame.h"

#include <chrono>
#include <cstdio>
#include <cmath>
#include <limits>

#include "kernels/shared/layout.h"
#include "kernels/shared/rng.h"

namespace tessera {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

struct Bounds {
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
};

Bounds scene_bounds(const SceneBuffers& s) {
    Bounds b;
    for (size_t i = 0; i < 3 * size_t(s.triangle_count); ++i)
        for (int a = 0; a < 3; ++a) {
            b.lo[a] = std::fmin(b.lo[a], s.tri_pos[3 * i + a]);
            b.hi[a] = std::fmax(b.hi[a], s.tri_pos[3 * i + a]);
        }
    return b;
}

// Copies floats offset..offset+2 of each pixel's `stride` floats into a 3-per-pixel array.
void extract3(const std::vector<float>& src, int stride, int offset, std::vector<float>& dst) {
    const size_t n = src.size() / stride;
    dst.resize(3 * n);
    for (size_t p = 0; p < n; ++p)
        for (int c = 0; c < 3; ++c) dst[3 * p + c] = src[p * stride + offset + c];
}

}  // namespace

IgiFrame::IgiFrame(Backend& backend, const SceneBuffers& scene, const EffectPlan& plan, const IgiSettings& settings)
    : backend_(backend), scene_(scene), plan_(plan), settings_(settings) {
    settings_.discontinuity.tile = static_cast<int>(settings.tile);
    const Bounds b = scene_bounds(scene);
    float diag2 = 0.0f;
    for (int a = 0; a < 3; ++a) diag2 += (b.hi[a] - b.lo[a]) * (b.hi[a] - b.lo[a]);
    const float c = settings.clamp_c;
    g_clamp_ = c > 0.0f ? 1.0f / (c * c * diag2) : std::numeric_limits<float>::infinity();
    // A ray that leaves the scene's bounds never returns: march at most this far.
    march_far_ = 2.0f * std::sqrt(diag2);
}

void IgiFrame::render(TsFrame frame, std::vector<float>& out) {
    const uint32_t n = settings_.tile, sets = n * n;
    frame.igi_tile = n;
    frame.shadow_samples = settings_.set_shadow_samples;
    frame.igi_steps = settings_.march_steps;
    frame.igi_g_clamp = g_clamp_;
    frame.igi_march_far = march_far_ + std::sqrt(frame.cam_pos[0] * frame.cam_pos[0] +
                                                 frame.cam_pos[1] * frame.cam_pos[1] +
                                                 frame.cam_pos[2] * frame.cam_pos[2]);
    // One Cranley–Patterson shift per frame, shared by all pixels (interleaved sampling).
    ts::TsRng rng = ts::ts_rng_seed(frame.seed, 0xffffffffu, frame.pass);
    for (float& r : frame.igi_rotation) r = ts::ts_rng_next(&rng);

    auto t0 = Clock::now();
    VplList vpls;
    if (plan_.indirect) {
        VplSettings vs;
        vs.sets = sets;
        vs.paths_per_set = settings_.paths_per_set;
        vs.frame = frame.pass;
        vpls = generate_vpls(backend_, scene_, vs);
    } else {  // nothing reflects: no light paths, no VPLs (the kernels see empty sets)
        vpls.set_start.assign(sets + 1, 0u);
        vpls.vpls.assign(TS_VPL_FLOATS, 0.0f);
    }
    backend_.set_vpls(vpls.vpls, vpls.set_start);
    stats_.vpls = vpls.count();
    stats_.vpl_rays = vpls.rays;
    stats_.vpl_seconds = since(t0);

    t0 = Clock::now();
    std::vector<float> surf, media;
    backend_.render_pass(PixelKernel::IgiSurface, frame, surf);
    stats_.surface_seconds = since(t0);
    const uint64_t pixels = uint64_t(frame.width) * frame.height;
    stats_.pixel_rays = pixels * (1 + settings_.set_shadow_samples + stats_.vpls / sets);
    stats_.media_seconds = 0.0;
    if (plan_.medium) {
        t0 = Clock::now();
        backend_.render_pass(PixelKernel::IgiMedia, frame, media);
        stats_.media_seconds = since(t0);
        stats_.pixel_rays += pixels * (1 + settings_.march_steps);
    }
    t0 = Clock::now();
    composite(static_cast<int>(frame.width), surf, media, out);
    stats_.filter_seconds = since(t0);
}

void IgiFrame::composite(int width, const std::vector<float>& surf, const std::vector<float>& media,
                         std::vector<float>& out) {
    const size_t pixels = surf.size() / TS_IGI_SURF_FLOATS;
    GeometryBuffer g;
    extract3(surf, TS_IGI_SURF_FLOATS, 0, ss_);
    extract3(surf, TS_IGI_SURF_FLOATS, 3, id_);
    pm_.assign(3 * pixels, 0.0f);
    std::vector<float> transmittance(3 * pixels, 1.0f);
    if (!media.empty()) {
        extract3(media, TS_IGI_MEDIA_FLOATS, 0, pm_);
        extract3(media, TS_IGI_MEDIA_FLOATS, 3, transmittance);
    }
    g.width = width;
    g.height = static_cast<int>(pixels / static_cast<size_t>(width));
    extract3(surf, TS_IGI_SURF_FLOATS, 12, g.normal);
    g.depth.resize(pixels);
    for (size_t p = 0; p < pixels; ++p) g.depth[p] = surf[p * TS_IGI_SURF_FLOATS + 15];
    if (settings_.filter) {
        discontinuity_filter(g, settings_.discontinuity, 3, ss_, ss_f_);
        discontinuity_filter(g, settings_.discontinuity, 3, id_, id_f_);
        discontinuity_filter(g, settings_.discontinuity, 3, pm_, pm_f_);
    } else {
        ss_f_ = ss_, id_f_ = id_, pm_f_ = pm_;
    }
    out.resize(pixels * TS_PASS_FLOATS);
    for (size_t p = 0; p < pixels; ++p) {
        const float* s = &surf[p * TS_IGI_SURF_FLOATS];
        float* o = &out[p * TS_PASS_FLOATS];
        for (int c = 0; c < 3; ++c) {
            const float e = ss_f_[3 * p + c] + id_f_[3 * p + c];
            o[c] = transmittance[3 * p + c] * s[16 + c] * (s[9 + c] + s[6 + c] * e) + pm_f_[3 * p + c];
            o[3 + c] = s[6 + c];
            o[6 + c] = s[12 + c];
        }
        o[9] = s[15];
    }
    const std::vector<float>* parts[6] = {&ss_, &ss_f_, &id_, &id_f_, &pm_, &pm_f_};
    for (int i = 0; i < 6; ++i) {
        if (component_sums_[i].size() != parts[i]->size()) component_sums_[i].assign(parts[i]->size(), 0.0);
        for (size_t j = 0; j < parts[i]->size(); ++j) component_sums_[i][j] += (*parts[i])[j];
    }
}

std::string IgiFrame::describe() const {
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "igi: tile %ux%u, %zu VPLs from %u paths per set (%llu light-path rays), G clamp %.4g, "
                  "last frame: VPLs %.1f ms, surface %.1f ms, media %.1f ms%s, filter+composite %.1f ms",
                  settings_.tile, settings_.tile, stats_.vpls, settings_.paths_per_set,
                  static_cast<unsigned long long>(stats_.vpl_rays), g_clamp_, 1e3 * stats_.vpl_seconds,
                  1e3 * stats_.surface_seconds, 1e3 * stats_.media_seconds, plan_.medium ? "" : " (no medium)",
                  1e3 * stats_.filter_seconds);
    return buf;
}

void IgiFrame::add_component_channels(Image& image, uint32_t frames) const {
    static const char* names[6] = {"SS", "SS_filtered", "ID", "ID_filtered", "PM", "PM_filtered"};
    static const char* rgb[3] = {"R", "G", "B"};
    for (int i = 0; i < 6; ++i) {
        if (component_sums_[i].empty() || (i >= 4 && !plan_.medium)) continue;  // PM only with a medium
        for (int c = 0; c < 3; ++c) {
            ImageChannel ch{std::string(names[i]) + "." + rgb[c], {}};
            ch.data.resize(component_sums_[i].size() / 3);
            for (size_t p = 0; p < ch.data.size(); ++p)
                ch.data[p] = static_cast<float>(component_sums_[i][3 * p + c] / frames);
            image.channels.push_back(std::move(ch));
        }
    }
}

}  // namespace tessera
