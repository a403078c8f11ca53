#include "integrators/igi_frame.h"

#include <chrono>
#include <initializer_list>
#include <cstdio>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "device/medium_view.h"
#include "gi/clamp_screen.h"
#include "integrators/settings.h"
#include "kernels/shared/composite.h"
#include "kernels/shared/frame.h"
#include "kernels/shared/layout_igi.h"
#include "kernels/shared/layout_pass.h"
#include "kernels/shared/rng.h"
#include "kernels/shared/sampling.h"

namespace tessera {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The clamp c of the VPL importance (VplSettings::importance_clamp): the default clamp's.
constexpr float kImportanceClampC = 0.1f;

// One field of a per-pixel record: `offset` within each pixel's floats, into `dst`
// (3 floats a pixel, or 1 for a scalar).
struct Field {
    int offset;
    std::vector<float>* dst;
    int floats = 3;
};

// Copies `fields` out of `src` (`stride` floats a pixel) in one parallel pass: a pass per
// field would read the whole 32 MB surface output (512²) once for each.
void extract_fields(const std::vector<float>& src, int stride, std::initializer_list<Field> fields) {
    const size_t n = src.size() / stride;
    for (const Field& f : fields) f.dst->resize(f.floats * n);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (const Field& f : fields) {
            float* dst = f.dst->data();
            for (size_t p = r.begin(); p < r.end(); ++p)
                for (int c = 0; c < f.floats; ++c) dst[f.floats * p + c] = src[p * stride + f.offset + c];
        }
    });
}

}  // namespace

IgiFrame::IgiFrame(Backend& backend, const SceneBuffers& scene, const EffectPlan& plan, const IgiSettings& settings)
    : backend_(backend), scene_(scene), plan_(plan), settings_(settings) {
    settings_.discontinuity.tile = static_cast<int>(settings.tile);
    const SceneBounds& b = scene.bounds;
    float diag2 = 0.0f;
    for (int a = 0; a < 3; ++a) diag2 += (b.hi[a] - b.lo[a]) * (b.hi[a] - b.lo[a]);
    // The clamps' D leaves outlying bits of surface out (SceneBuffers::clamp_length); the march's length
    // below needs the whole bounds.
    const float d = scene.clamp_length, c = settings.clamp_c;
    g_clamp_ = c > 0.0f ? 1.0f / (c * c * d * d) : std::numeric_limits<float>::infinity();
    importance_clamp_ = 1.0f / (kImportanceClampC * kImportanceClampC * d * d);
    // A ray that leaves the scene's bounds never returns: march at most this far.
    march_far_ = 2.0f * std::sqrt(diag2);
}

ViewPoints IgiFrame::view_points(const TsFrame& frame) {
    if (settings_.view_history) return settings_.view_history->points_for(backend_, scene_, frame, settings_.view_grid);
    return trace_view_points(backend_, scene_, frame, settings_.view_grid);
}

float IgiFrame::g_clamp_for(uint32_t pass) const {
    if (!(settings_.clamp_decay > 0.0f)) return g_clamp_;
    // b ∝ 1/c², so c_p = c · (p + 1)^-a gives b_p = b · (p + 1)^(2a).
    return g_clamp_ * std::pow(static_cast<float>(pass) + 1.0f, 2.0f * settings_.clamp_decay);
}

TsFrame IgiFrame::prepare(TsFrame frame) const {
    frame.igi_tile = settings_.tile;
    frame.shadow_samples = settings_.set_shadow_samples;
    frame.igi_steps = settings_.march_steps;
    frame.igi_g_clamp = g_clamp_for(frame.pass);
    // The kernels see the light-transport components only; edges are host scheduling.
    frame.igi_components = effective_components() & ~TS_COMPONENT_EDGE;
    // A medium out of every camera ray's reach this frame: each pixel's march would give
    // in-scattered light 0 and transmittance 1, so PM is skipped with the same image.
    if ((frame.igi_components & TS_COMPONENT_PM) &&
        !camera_may_meet_medium(frame, ts::ts_medium_load(scene_.medium.data())))
        frame.igi_components &= ~TS_COMPONENT_PM;
    frame.igi_media_vpls = !settings_.multiple_scattering ? TS_MEDIA_VPLS_NONE
                           : settings_.ray_lights         ? TS_MEDIA_VPLS_RAYS
                                                          : TS_MEDIA_VPLS_POINTS;
    frame.igi_equiangular = settings_.equiangular ? 1u : 0u;
    frame.igi_filter = settings_.filter ? 1u : 0u;
    frame.igi_filter_cos = settings_.discontinuity.normal_cos;
    frame.igi_filter_depth = settings_.discontinuity.depth_rel;
    // Read by the device resolve only; the host's reconstruction asks compensates_clamp().
    frame.igi_clamp_screen = compensates_clamp() && (frame.igi_components & TS_COMPONENT_ID) ? 1u : 0u;
    frame.igi_march_far = march_far_ + std::sqrt(frame.cam_pos[0] * frame.cam_pos[0] +
                                                 frame.cam_pos[1] * frame.cam_pos[1] +
                                                 frame.cam_pos[2] * frame.cam_pos[2]);
    // One Cranley–Patterson shift per frame, shared by all pixels (interleaved sampling).
    ts::TsRng rng = ts::ts_rng_seed(frame.seed, 0xffffffffu, frame.pass);
    for (float& r : frame.igi_rotation) r = ts::ts_rng_next(&rng);
    // The march's own shift: with igi_rotation[0] each step's distance moved with its light
    // sample's point, a correlation that biased the march (+0.9% on the single-scattering
    // quadrature at one 4-step pass, tests/integrators/igi_frame_test.cpp).
    frame.igi_march_rotation = ts::ts_rng_next(&rng);
    return frame;
}

void IgiFrame::render_pass(const TsFrame& unprepared, std::vector<float>& out) {
    const uint32_t sets = settings_.tile * settings_.tile;
    const TsFrame frame = prepare(unprepared);
    auto t0 = Clock::now();
    stats_.view_seconds = stats_.paths_seconds = stats_.select_seconds = 0.0;
    stats_.paths_kernel_seconds = stats_.select_kernel_seconds = stats_.resolve_kernel_seconds = 0.0;
    VplList vpls;
    // The scene's components, not this frame's: a frame with PM out of view still makes
    // the sets the march would gather, so the view points' history (the viewer) and every
    // later frame stay as they were.
    if (needs_vpl_sets(effective_components())) {
        VplSettings vs;
        vs.sets = sets;
        vs.paths_per_set = settings_.paths_per_set;
        vs.max_bounces = settings_.light_path_depth;
        vs.frame = frame.pass;
        vs.seed = frame.seed;
        vs.medium_scattering = settings_.multiple_scattering;
        // Ray lights carry the light a medium scatters: none where it only absorbs.
        vs.ray_lights = settings_.multiple_scattering && settings_.ray_lights && plan_.medium_scatters;
        ViewPoints view;
        if (settings_.vpl_importance > 1) {
            const auto tv = Clock::now();
            view = view_points(frame);
            stats_.view_seconds = since(tv);
            vs.importance_oversampling = settings_.vpl_importance;
            vs.view = &view;
            vs.importance_clamp = importance_clamp_;
        }
        vpls = generate_vpls(backend_, scene_, vs);
        stats_.paths_seconds = vpls.trace_seconds;
        stats_.select_seconds = vpls.select_seconds;
        stats_.paths_kernel_seconds = vpls.trace_kernel_seconds;
        stats_.select_kernel_seconds = vpls.select_kernel_seconds;
    } else {  // nothing reflects: no light paths, no VPLs (the kernels see empty sets)
        vpls.set_start.assign(sets + 1, 0u);
        vpls.vpls.assign(TS_VPL_FLOATS, 0.0f);
    }
    backend_.set_input(KernelInput::Vpls, vpls.vpls);
    backend_.set_input(KernelInput::VplSetStart, vpls.set_start);
    if (frame.igi_media_vpls == TS_MEDIA_VPLS_RAYS) {
        if (vpls.vrls.empty()) {
            vpls.vrls.assign(TS_VRL_FLOATS, 0.0f);
            vpls.vrl_set_start.assign(sets + 1, 0u);
        }
        backend_.set_input(KernelInput::Vrls, vpls.vrls);
        backend_.set_input(KernelInput::VrlSetStart, vpls.vrl_set_start);
    }
    stats_.vpls = vpls.count();
    stats_.vpl_rays = vpls.rays;
    stats_.vpl_seconds = since(t0);
    stats_.medium_out_of_view = (effective_components() & TS_COMPONENT_PM) && !(frame.igi_components & TS_COMPONENT_PM);

    TsFrame surface_frame = frame;
    if (!interleaved_indirect()) surface_frame.igi_components &= ~TS_COMPONENT_ID;
    const uint64_t pixels = uint64_t(frame.width) * frame.height;
    const bool surface_vpls = surface_frame.igi_components & TS_COMPONENT_ID;
    stats_.pixel_rays = pixels * (1 + settings_.set_shadow_samples + (surface_vpls ? stats_.vpls / sets : 0));
    if (frame.igi_components & TS_COMPONENT_PM)
        stats_.pixel_rays += pixels * (1 + (plan_.medium_scatters ? settings_.march_steps : 0));
    if (!reconstructs_on_host()) return resolve_on_device(frame, surface_frame, out);

    t0 = Clock::now();
    std::vector<float>&surf = surf_, &media = media_;
    media.clear();
    backend_.launch(KernelId::IgiSurface, surface_frame, surf);
    stats_.surface_seconds = since(t0);
    stats_.media_seconds = 0.0;
    if (frame.igi_components & TS_COMPONENT_PM) {
        t0 = Clock::now();
        backend_.launch(KernelId::IgiMedia, frame, media);
        stats_.media_seconds = since(t0);
    }
    t0 = Clock::now();
    extract(static_cast<int>(frame.width), surf, media);
    // The window tests once per frame, for every component and AIS's guidance.
    if (settings_.filter) discontinuity_precompute(geometry_, settings_.discontinuity);
    const auto tr = Clock::now();
    refine(frame, surf, media);
    t0 += Clock::now() - tr;
    // This frame's components: PM may be out of view (prepare).
    const uint32_t bits = frame.igi_components;
    for (int c = 0; c < kAisComponents; ++c) {
        if (bits & (1u << c)) reconstruct_component(c);
        else final_[c] = raw_[c];  // not computed: zeros, which the filter would keep
    }
    if (compensates_clamp() && (bits & TS_COMPONENT_ID)) compensate_clamp(frame, surf);
    composite(surf, out);
    finish(frame, out);
    if (settings_.component_aovs) add_to_sums();
    // finish() timed AIS's edges as a stage of their own.
    stats_.filter_seconds = std::max(0.0, since(t0) - stats_.edge_seconds);
}

bool IgiFrame::needs_vpl_sets(uint32_t components) const {
    // Surfaces gather the sets for ID where the sets make it; the ray march gathers them
    // for light scattered more than once, whatever makes ID (ic's cache, or nothing).
    const bool for_id = plan_.indirect && (components & TS_COMPONENT_ID) && interleaved_indirect();
    const bool for_media =
        plan_.area_lights && plan_.medium_scatters && (components & TS_COMPONENT_PM) && settings_.multiple_scattering;
    return for_id || for_media;
}

void IgiFrame::resolve_on_device(const TsFrame& frame, const TsFrame& surface_frame, std::vector<float>& out) {
    // Queued without a wait between the launches; the one read-back is the image.
    const auto t0 = Clock::now();
    backend_.launch_into(KernelId::IgiSurface, surface_frame, KernelInput::IgiSurface);
    const bool media = frame.igi_components & TS_COMPONENT_PM;
    if (media) backend_.launch_into(KernelId::IgiMedia, frame, KernelInput::IgiMedia);
    if (frame.igi_clamp_screen) {
        backend_.launch_into(KernelId::IgiClampRecords, frame, KernelInput::ClampRecords);
        backend_.launch_into(KernelId::IgiClampGather, frame, KernelInput::ClampResidual);
    }
    backend_.launch(resolve_kernel(), frame, out);
    stats_.surface_seconds = backend_.kernel_seconds(KernelId::IgiSurface);
    stats_.media_seconds = media ? backend_.kernel_seconds(KernelId::IgiMedia) : 0.0;
    // The rest of the wall time: the filter's kernels, the read-back and the gaps.
    stats_.filter_seconds = std::max(0.0, since(t0) - stats_.surface_seconds - stats_.media_seconds);
    stats_.resolve_kernel_seconds = resolve_kernels_seconds(frame, resolve_kernel());
}

double IgiFrame::resolve_kernels_seconds(const TsFrame& frame, KernelId resolve) {
    double s = backend_.kernel_seconds(resolve);
    if (frame.igi_clamp_screen)
        s += backend_.kernel_seconds(KernelId::IgiClampRecords) + backend_.kernel_seconds(KernelId::IgiClampGather);
    return s;
}

bool IgiFrame::compensates_clamp() const {
    return settings_.clamp_compensation && interleaved_indirect() && plan_.indirect && std::isfinite(g_clamp_);
}

void IgiFrame::compensate_clamp(const TsFrame& frame, const std::vector<float>& surf) {
    ClampScreenInputs in;
    in.g = &geometry_;
    in.albedo = in.throughput = &surf;
    in.stride = TS_IGI_SURF_FLOATS;
    in.albedo_at = TS_IGI_SURF_ALBEDO;
    in.throughput_at = TS_IGI_SURF_THROUGHPUT;
    in.e_ss = &final_[kAisSS];
    in.e_id = &final_[kAisID];
    in.same_surface = settings_.discontinuity;
    ts::TsMedium medium;
    if (plan_.medium) medium = ts::ts_medium_load(scene_.medium.data());
    clamp_screen_residual(frame, frame.igi_g_clamp, plan_.medium ? &medium : nullptr, in, clamp_residual_,
                          clamp_planes_);
    std::vector<float>& e_id = final_[kAisID];
    for (size_t j = 0; j < e_id.size(); ++j) e_id[j] += clamp_residual_[j];
}

void IgiFrame::extract(int width, const std::vector<float>& surf, const std::vector<float>& media) {
    const size_t pixels = surf.size() / TS_IGI_SURF_FLOATS;
    extract_fields(surf, TS_IGI_SURF_FLOATS,
                   {{TS_IGI_SURF_E_SS, &raw_[kAisSS]},
                    {TS_IGI_SURF_E_ID, &raw_[kAisID]},
                    {TS_IGI_SURF_NORMAL, &geometry_.normal},
                    {TS_IGI_SURF_POSITION, &geometry_.position},
                    {TS_IGI_SURF_DISTANCE, &geometry_.depth, 1}});
    if (!media.empty()) {
        extract_fields(media, TS_IGI_MEDIA_FLOATS,
                       {{TS_IGI_MEDIA_RADIANCE, &raw_[kAisPM]}, {TS_IGI_MEDIA_TRANSMITTANCE, &transmittance_}});
    } else {
        raw_[kAisPM].assign(3 * pixels, 0.0f);
        transmittance_.assign(3 * pixels, 1.0f);
    }
    geometry_.width = width;
    geometry_.height = static_cast<int>(pixels / static_cast<size_t>(width));
}

void IgiFrame::reconstruct_component(int c) {
    if (!settings_.filter)
        final_[c] = raw_[c];
    else
        discontinuity_filter(geometry_, settings_.discontinuity, 3, raw_[c], final_[c]);
}

void IgiFrame::composite(const std::vector<float>& surf, std::vector<float>& out) {
    const size_t pixels = surf.size() / TS_IGI_SURF_FLOATS;
    out.resize(pixels * TS_PASS_FLOATS);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, pixels, 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t p = r.begin(); p < r.end(); ++p) {
            const float* s = &surf[p * TS_IGI_SURF_FLOATS];
            float* o = &out[p * TS_PASS_FLOATS];
            auto at = [p](const std::vector<float>& v) { return ts::ts_f3_load(&v[3 * p]); };
            ts::ts_f3_store(o + TS_PASS_RADIANCE,
                            ts::ts_igi_composite(at(transmittance_), ts::ts_f3_load(s + TS_IGI_SURF_THROUGHPUT),
                                                 ts::ts_f3_load(s + TS_IGI_SURF_EMISSION),
                                                 ts::ts_f3_load(s + TS_IGI_SURF_ALBEDO), at(final_[kAisSS]),
                                                 at(final_[kAisID]), at(final_[kAisPM])));
            for (int c = 0; c < 3; ++c) {
                o[TS_PASS_ALBEDO + c] = s[TS_IGI_SURF_ALBEDO + c];
                o[TS_PASS_NORMAL + c] = s[TS_IGI_SURF_NORMAL + c];
            }
            o[TS_PASS_DEPTH] = s[TS_IGI_SURF_DISTANCE];
        }
    });
}

void IgiFrame::add_to_sums() {
    auto add = [](std::vector<double>& sum, const auto& v) {
        if (sum.size() != v.size()) sum.assign(v.size(), 0.0);
        for (size_t j = 0; j < v.size(); ++j) sum[j] += v[j];
    };
    for (int c = 0; c < kAisComponents; ++c) {
        add(component_sums_[2 * c], raw_[c]);
        add(component_sums_[2 * c + 1], final_[c]);
    }
}

std::string IgiFrame::describe() const {
    char buf[520], view[64] = "", paths_kernel[32] = "", select_kernels[32] = "", resolve_kernels[32] = "";
    if (settings_.vpl_importance > 1)
        std::snprintf(view, sizeof view, ", kept for the view from %ux", settings_.vpl_importance);
    // Where a part ran kernels on the device, their share of its wall time: the rest is
    // transfers and waits, which is what a GPU's stage times leave open.
    auto kernel_share = [](char (&note)[32], const char* label, double seconds) {
        if (seconds > 0.0) std::snprintf(note, sizeof note, " (%s %.2f)", label, 1e3 * seconds);
    };
    kernel_share(paths_kernel, "kernel", stats_.paths_kernel_seconds);
    kernel_share(select_kernels, "kernels", stats_.select_kernel_seconds);
    kernel_share(resolve_kernels, "kernels", stats_.resolve_kernel_seconds);
    const char* media_note = !plan_.medium ? " (no medium)" : stats_.medium_out_of_view ? " (out of view)" : "";
    // No light path traced (ic or tic on a clear scene, whose cache carries the indirect
    // light): the VPL settings were not read, so they are not shown.
    if (stats_.vpls == 0 && stats_.vpl_rays == 0) {
        std::snprintf(buf, sizeof buf,
                      "igi: tile %ux%u, no VPL sets traced, last frame: surface %.1f ms, media %.1f ms%s, "
                      "filter+composite %.1f ms%s",
                      settings_.tile, settings_.tile, 1e3 * stats_.surface_seconds, 1e3 * stats_.media_seconds,
                      media_note, 1e3 * stats_.filter_seconds, resolve_kernels);
        return buf;
    }
    std::snprintf(buf, sizeof buf,
                  "igi: tile %ux%u, %zu VPLs from %u paths per set%s (%llu light-path rays), G clamp %.4g, "
                  "last frame: VPLs %.1f ms (view points %.1f, paths %.1f%s, selection %.1f%s), surface %.1f ms, "
                  "media %.1f ms%s, filter+composite %.1f ms%s",
                  settings_.tile, settings_.tile, stats_.vpls, settings_.paths_per_set, view,
                  static_cast<unsigned long long>(stats_.vpl_rays), g_clamp_, 1e3 * stats_.vpl_seconds,
                  1e3 * stats_.view_seconds, 1e3 * stats_.paths_seconds, paths_kernel, 1e3 * stats_.select_seconds,
                  select_kernels,
                  1e3 * stats_.surface_seconds, 1e3 * stats_.media_seconds, media_note,
                  1e3 * stats_.filter_seconds, resolve_kernels);
    return buf;
}

void IgiFrame::report(IntegratorStats& stats) const {
    stats.detail = describe();
    stats.igi = stats_;
}

void IgiFrame::add_aov_channels(Image& image, uint32_t frames) const {
    static const char* names[6] = {"SS", "SS_filtered", "ID", "ID_filtered", "PM", "PM_filtered"};
    const uint32_t bits = effective_components();
    for (int i = 0; i < 6; ++i)
        if (bits & (1u << (i / 2))) append_channels(image, component_sums_[i], names[i], 3, frames);
}

std::vector<std::vector<double>*> IgiFrame::aov_sums() {
    std::vector<std::vector<double>*> sums;
    for (auto& s : component_sums_) sums.push_back(&s);
    return sums;
}

void IgiFrame::append_channels(Image& image, const std::vector<double>& sum, const std::string& name, int channels,
                               uint32_t frames) {
    static const char* rgb[3] = {"R", "G", "B"};
    if (sum.empty()) return;
    for (int c = 0; c < channels; ++c) {
        ImageChannel ch{channels == 3 ? name + "." + rgb[c] : name, {}};
        ch.data.resize(sum.size() / channels);
        for (size_t p = 0; p < ch.data.size(); ++p) ch.data[p] = static_cast<float>(sum[channels * p + c] / frames);
        image.channels.push_back(std::move(ch));
    }
}

uint32_t IgiFrame::effective_components() const {
    uint32_t bits = settings_.components;
    if (!plan_.medium) bits &= ~TS_COMPONENT_PM;
    if (!plan_.area_lights) bits &= ~TS_COMPONENT_SS;
    // Nothing reflects diffusely: ID is black, and AIS would still guide and refine it.
    if (!plan_.indirect) bits &= ~TS_COMPONENT_ID;
    return bits;
}

}  // namespace tessera
