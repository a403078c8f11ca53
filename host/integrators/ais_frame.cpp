#include "integrators/ais_frame.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "gi/ais_items.h"
#include "gi/ais_reconstruct.h"
#include "kernels/shared/frame.h"
#include "kernels/shared/layout_igi.h"
#include "kernels/shared/sampling.h"

namespace tessera {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// f(p) for p in [0, pixels), over TBB.
template <class F>
void parallel_pixels(size_t pixels, F&& f) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, pixels, 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t p = r.begin(); p < r.end(); ++p) f(p);
    });
}

}  // namespace

void AisFrame::refine(const TsFrame& frame, const std::vector<float>& surf, const std::vector<float>& media) {
    const auto t0 = Clock::now();
    add_sets(frame, surf, media);
    stats_.ais_seconds = since(t0);
}

// The guidance's inputs from the surface and media kernels' outputs.
AisBaseBuffers AisFrame::base_of(const std::vector<float>& surf, const std::vector<float>& media) const {
    const size_t pixels = surf.size() / TS_IGI_SURF_FLOATS;
    AisBaseBuffers base;
    base.visibility.resize(pixels);
    base.indirect.resize(pixels);
    if (!media.empty()) {
        base.lit_fraction.resize(pixels);
        base.medium_length.resize(pixels);
        if (settings_.ais.pm_cov > 0.0f) base.media.resize(pixels);  // read only by g_var
    }
    parallel_pixels(pixels, [&](size_t p) {
        const float* v = &surf[p * TS_IGI_SURF_FLOATS];
        base.visibility[p] = v[TS_IGI_SURF_VISIBLE];
        base.indirect[p] = ts::ts_luminance(ts::ts_f3_load(v + TS_IGI_SURF_E_ID));
        if (media.empty()) return;
        base.lit_fraction[p] = media[p * TS_IGI_MEDIA_FLOATS + TS_IGI_MEDIA_LIT];
        base.medium_length[p] = media[p * TS_IGI_MEDIA_FLOATS + TS_IGI_MEDIA_LENGTH];
        if (!base.media.empty())
            base.media[p] = ts::ts_luminance(ts::ts_f3_load(&media[p * TS_IGI_MEDIA_FLOATS + TS_IGI_MEDIA_RADIANCE]));
    });
    return base;
}

AisThresholds AisFrame::thresholds() const {
    // The set-to-set CoV that VPL noise alone gives falls as 1/√paths: id_cov is stated
    // for kIdCovPaths paths per set and scaled to this frame's.
    AisThresholds t = settings_.ais;
    t.id_cov *= std::sqrt(float(AisThresholds::kIdCovPaths) / float(std::max(1u, settings_.paths_per_set)));
    return t;
}

// Guidance from the base pass and the schedule: the extra sets' item list.
std::vector<uint32_t> AisFrame::schedule_sets(AisBaseBuffers base) {
    // The G-buffer is lent to the guidance, not copied (9 MB at 512², 3 ms), and taken back.
    base.geometry = std::move(geometry_);
    const uint32_t bits = effective_components();
    const std::array<bool, kAisComponents> enabled = {(bits & TS_COMPONENT_SS) != 0, (bits & TS_COMPONENT_ID) != 0,
                                                      (bits & TS_COMPONENT_PM) != 0 && plan_.medium_scatters &&
                                                          !base.lit_fraction.empty()};
    const AisThresholds t = thresholds();
    guidance_ = compute_guidance(base, settings_.discontinuity, t, enabled);
    geometry_ = std::move(base.geometry);
    schedule_ = make_schedule(guidance_, t, settings_.ais_mode, geometry_.width, geometry_.height,
                              static_cast<int>(settings_.tile));
    return item_list();
}

std::vector<uint32_t> AisFrame::item_list() {
    stats_.flagged = schedule_.flagged;
    stats_.ais_items = schedule_.item_pixels.size();
    static_assert(1u << kAisSS == TS_COMPONENT_SS && 1u << kAisID == TS_COMPONENT_ID &&
                  1u << kAisPM == TS_COMPONENT_PM, "AIS component bits are the kernels' TS_COMPONENT_* bits");
    dispatch_ = ais_dispatch_order(schedule_);
    return ais_item_list(schedule_, dispatch_);
}

// AIS: guidance from the base pass, the schedule, the extra sets; each refined pixel's
// raw component becomes the mean over all the sets it evaluated (summed in double: own
// set first, then the extra sets in increasing order), its base estimate kept for the
// neighbours' reconstruction.
void AisFrame::add_sets(const TsFrame& frame, const std::vector<float>& surf, const std::vector<float>& media) {
    const size_t pixels = raw_[kAisSS].size() / 3;
    const auto t_schedule = Clock::now();
    const std::vector<uint32_t> list = schedule_sets(base_of(surf, media));
    stats_.ais_schedule_seconds = since(t_schedule);
    const auto t_kernel = Clock::now();
    std::vector<float> dispatched, items;
    backend_.launch_items(KernelId::AisItem, frame, list, dispatched);
    stats_.ais_kernel_seconds = since(t_kernel);
    const auto t_merge = Clock::now();
    // The kernels wrote the items in dispatch order (ais_dispatch_order); back to the schedule's.
    items.resize(dispatched.size());
    for (size_t j = 0; j < dispatch_.size(); ++j)
        std::copy_n(&dispatched[j * TS_AIS_ITEM_FLOATS], TS_AIS_ITEM_FLOATS,
                    &items[size_t(dispatch_[j]) * TS_AIS_ITEM_FLOATS]);
    // own_sum_ is read only where a pixel evaluated more than its own set
    // (ais_reconstruct); elsewhere it is left unset, and raw_ = own sum / 1 unchanged.
    for (int c = 0; c < kAisComponents; ++c) {
        base_[c] = raw_[c];
        if (schedule_.sets[c].empty()) {
            own_sum_[c].clear();
            continue;
        }
        own_sum_[c].resize(raw_[c].size());
        parallel_pixels(pixels, [&](size_t p) {
            if (schedule_.sets[c][p] < 2) return;
            for (int j = 0; j < 3; ++j) own_sum_[c][3 * p + j] = raw_[c][3 * p + j];
        });
    }
    // Item order: each pixel's extra sets in increasing order.
    for (size_t i = 0; i < schedule_.item_pixels.size(); ++i) {
        const size_t p = schedule_.item_pixels[i];
        for (int c = 0; c < kAisComponents; ++c)
            if (schedule_.item_components[i] & (1u << c))
                for (int j = 0; j < 3; ++j) own_sum_[c][3 * p + j] += items[i * TS_AIS_ITEM_FLOATS + TS_AIS_ITEM_COMPONENT(c) + j];
    }
    for (int c = 0; c < kAisComponents; ++c) {
        if (schedule_.sets[c].empty()) continue;
        parallel_pixels(pixels, [&](size_t p) {
            if (schedule_.sets[c][p] < 2) return;
            for (int j = 0; j < 3; ++j)
                raw_[c][3 * p + j] = static_cast<float>(own_sum_[c][3 * p + j] / schedule_.sets[c][p]);
        });
    }
    stats_.ais_merge_seconds = since(t_merge);
}

// Each component: the discontinuity filter over the interleaved estimates; with AIS,
// pixels the schedule gave extra sets combine them with the accepted neighbours' sets
// they did not evaluate (ais_reconstruct.h: each set at most once; all N sets: the pixel's own
// full-rate mean, unfiltered: docs/ais.md §6).
void AisFrame::reconstruct_component(int c) {
    if (settings_.filter && !schedule_.sets[c].empty())
        ais_reconstruct(geometry_, settings_.discontinuity, base_[c], own_sum_[c], schedule_.masks[c], final_[c]);
    else
        IgiFrame::reconstruct_component(c);
}

void AisFrame::schedule_edges(const std::vector<float>& out) {
    edge_guidance_ = edge_guidance(geometry_, settings_.discontinuity, out, settings_.edges.dark, emitter_);
    edge_schedule_ = make_edge_schedule(edge_guidance_, settings_.edges, settings_.ais_mode);
    stats_.edge_samples = edge_schedule_.items.size() / TS_EDGE_ITEM_WORDS;
    stats_.edge_flagged = edge_schedule_.flagged;
}

void AisFrame::finish(const TsFrame& frame, std::vector<float>& out) {
    edge_guidance_.clear();
    edge_schedule_ = EdgeSchedule{};
    stats_.edge_samples = 0;
    stats_.edge_flagged = 0;
    stats_.edge_seconds = 0;
    if (!(effective_components() & TS_COMPONENT_EDGE)) return;
    const auto t0 = Clock::now();
    // Where each camera path ends on a light: a light's edge in its holder's plane.
    const size_t pixels = surf_.size() / TS_IGI_SURF_FLOATS;
    emitter_.assign(pixels, 0);
    parallel_pixels(pixels, [&](size_t p) {
        const float* le = &surf_[p * TS_IGI_SURF_FLOATS + TS_IGI_SURF_EMISSION];
        emitter_[p] = le[0] + le[1] + le[2] > 0.0f;
    });
    schedule_edges(out);
    const auto t_kernel = Clock::now();
    backend_.launch_items(KernelId::EdgeSample, frame, edge_schedule_.items, edge_samples_);
    const auto t_merge = Clock::now();
    merge_edge_samples(geometry_, settings_.discontinuity, edge_schedule_, edge_samples_,
                       {&final_[kAisSS], &final_[kAisID], &final_[kAisPM], &transmittance_}, out);
    stats_.edge_seconds = since(t0);
    stats_.edge_schedule_seconds = std::chrono::duration<double>(t_kernel - t0).count();
    stats_.edge_kernel_seconds = std::chrono::duration<double>(t_merge - t_kernel).count();
}

void AisFrame::resolve_on_device(const TsFrame& frame, const TsFrame& surface_frame, std::vector<float>& out) {
    // The base pass's outputs stay on the device, and so do the schedule kernels' masks
    // and counts: the host reads per-tile counts back (gi/ais_items.h). Launches queue
    // without a wait; the host waits only for what it reads (the counts, the image), so
    // the kernels' stage times are their own (Backend::kernel_seconds) and the host's
    // parts are timed between those reads.
    const auto t0 = Clock::now();
    const bool media = frame.igi_components & TS_COMPONENT_PM;
    const uint32_t bits = effective_components();
    // PM is guided where the medium scatters: one that only absorbs has no light to refine.
    const uint32_t guided =
        bits & (TS_COMPONENT_SS | TS_COMPONENT_ID | (media && plan_.medium_scatters ? TS_COMPONENT_PM : 0u));
    schedule_table_ = ais_schedule_table(thresholds(), settings_.ais_mode, static_cast<int>(settings_.tile), guided,
                                         settings_.edges, 0.0f);
    // No host schedule: the masks stay on the device, the host reads each (set, tile)'s
    // count and uploads their prefix sums (gi/ais_items.h; the guidance and set-count maps
    // are AOVs, which the host path draws). Unguided components keep their own set, so
    // with none guided every count is 0. The table goes first: an upload queued behind
    // the base pass would wait for it.
    guidance_ = AisGuidance{};
    schedule_ = AisSchedule{};
    backend_.set_input(KernelInput::AisScheduleTable, schedule_table_);
    backend_.launch_into(KernelId::IgiSurface, surface_frame, KernelInput::IgiSurface);
    if (media) backend_.launch_into(KernelId::IgiMedia, frame, KernelInput::IgiMedia);
    backend_.launch_into(KernelId::AisSchedule, frame, KernelInput::AisMasks);
    const size_t tiles = ais_tile_count(frame.width, frame.height), pixels = size_t(frame.width) * frame.height;
    const size_t sets = size_t(frame.igi_tile) * frame.igi_tile;
    backend_.launch_count_into(KernelId::AisTileSets, frame, sets * tiles, KernelInput::AisTileSets);
    backend_.read_input(KernelInput::AisTileSets, tile_sets_);
    const auto t_offsets = Clock::now();
    ais_item_offsets(tile_sets_, sets, tiles, pixels, item_offsets_);
    backend_.set_input(KernelInput::AisItemOffsets, item_offsets_.offsets);
    stats_.flagged = item_offsets_.flagged;
    stats_.ais_items = item_offsets_.items();
    const double offsets_seconds = since(t_offsets);
    backend_.launch_count_into(KernelId::AisCompactItem, frame, item_offsets_.items(), KernelInput::AisItems);
    TsFrame ais = frame;
    ais.igi_ais = 1u;
    if (ais.igi_clamp_screen) {
        backend_.launch_into(KernelId::IgiClampRecords, ais, KernelInput::ClampRecords);
        backend_.launch_into(KernelId::IgiClampGather, ais, KernelInput::ClampResidual);
    }
    edge_guidance_.clear();
    edge_schedule_ = EdgeSchedule{};
    stats_.edge_samples = 0;
    stats_.edge_flagged = stats_.edge_seconds = stats_.edge_schedule_seconds = stats_.edge_kernel_seconds = 0.0;
    stats_.edge_schedule_kernel_seconds = 0.0;
    // With edges the whole pass stays on the device: the edge schedule reads its radiance.
    const KernelId resolve = bits & TS_COMPONENT_EDGE ? KernelId::IgiResolve : resolve_kernel();
    if (!(bits & TS_COMPONENT_EDGE)) {
        backend_.launch(resolve, ais, out);
    } else {
        backend_.launch_into(resolve, ais, KernelInput::IgiPass);
        edges_on_device(frame, ais, out);
    }
    const double wall = since(t0);
    stats_.surface_seconds = backend_.kernel_seconds(KernelId::IgiSurface);
    stats_.media_seconds = media ? backend_.kernel_seconds(KernelId::IgiMedia) : 0.0;
    stats_.ais_schedule_kernel_seconds =
        backend_.kernel_seconds(KernelId::AisSchedule) + backend_.kernel_seconds(KernelId::AisTileSets);
    stats_.ais_schedule_seconds = stats_.ais_schedule_kernel_seconds + offsets_seconds;
    stats_.ais_kernel_seconds = backend_.kernel_seconds(KernelId::AisCompactItem);
    stats_.ais_merge_seconds = 0.0;  // in the resolve
    stats_.ais_seconds = stats_.ais_schedule_seconds + stats_.ais_kernel_seconds;
    // The rest of the wall time but the edges' stage: the clamp's and the resolve's
    // kernels, the read-backs and the gaps.
    stats_.filter_seconds = std::max(
        0.0, wall - stats_.surface_seconds - stats_.media_seconds - stats_.ais_seconds - stats_.edge_seconds);
    stats_.resolve_kernel_seconds = resolve_kernels_seconds(ais, resolve);
}

void AisFrame::edges_on_device(const TsFrame& frame, const TsFrame& ais, std::vector<float>& out) {
    // The edge schedule from the resolved pass where it lies (IgiPass): its ε from the
    // rows' luminance sums, the counts from the schedule kernel; the image is read back
    // once, merged or not. Kernel stage times as resolve_on_device's.
    backend_.launch_count(KernelId::EdgeRowSums, ais, frame.height, row_sums_);
    auto t_host = Clock::now();
    const float eps = edge_epsilon_of_rows(row_sums_, size_t(frame.width) * frame.height, settings_.edges.dark);
    schedule_table_[TS_AIS_TABLE_EDGE_EPSILON] = std::bit_cast<uint32_t>(eps);
    backend_.set_input(KernelInput::AisScheduleTable, schedule_table_);
    double host_seconds = since(t_host);
    backend_.launch_into(KernelId::EdgeSchedule, ais, KernelInput::EdgeCounts);
    backend_.launch_count(KernelId::EdgeSegmentCounts, ais, ais_tile_count(frame.width, frame.height) * TS_AIS_TILE,
                          edge_segments_);
    t_host = Clock::now();
    edge_segment_offsets(edge_segments_, size_t(frame.width) * frame.height, edge_offsets_);
    stats_.edge_samples = edge_offsets_.samples();
    stats_.edge_flagged = edge_offsets_.flagged;
    if (edge_offsets_.samples() > 0) backend_.set_input(KernelInput::EdgeSegmentOffsets, edge_offsets_.offsets);
    host_seconds += since(t_host);
    const KernelId merge = settings_.pass_aovs ? KernelId::AisEdgeMerge : KernelId::AisEdgeMergeRadiance;
    if (edge_offsets_.samples() > 0) {
        backend_.launch_count_into(KernelId::EdgeCompactSample, frame, edge_offsets_.samples(),
                                   KernelInput::EdgeSamples);
        backend_.launch(merge, ais, out);
    } else {
        // Nothing to merge: the resolved pass as it lies, or its radiance.
        if (settings_.pass_aovs)
            backend_.read_input(KernelInput::IgiPass, out);
        else
            backend_.launch(KernelId::PassRadiance, ais, out);
    }
    stats_.edge_schedule_kernel_seconds = backend_.kernel_seconds(KernelId::EdgeRowSums) +
                                          backend_.kernel_seconds(KernelId::EdgeSchedule) +
                                          backend_.kernel_seconds(KernelId::EdgeSegmentCounts);
    stats_.edge_schedule_seconds = stats_.edge_schedule_kernel_seconds + host_seconds;
    // The image's read-back is the filter's stage's, with or without samples to merge.
    stats_.edge_kernel_seconds = edge_offsets_.samples() > 0 ? backend_.kernel_seconds(KernelId::EdgeCompactSample) +
                                                                   backend_.kernel_seconds(merge)
                                                             : 0.0;
    stats_.edge_seconds = stats_.edge_schedule_seconds + stats_.edge_kernel_seconds;
}

void AisFrame::add_to_sums() {
    IgiFrame::add_to_sums();
    auto add = [](std::vector<double>& sum, const auto& v) {
        if (sum.size() != v.size()) sum.assign(v.size(), 0.0);
        for (size_t j = 0; j < v.size(); ++j) sum[j] += v[j];
    };
    for (int c = 0; c < kAisComponents; ++c) {
        if (!guidance_.g[c].empty()) add(guidance_sums_[c], guidance_.g[c]);
        if (!schedule_.sets[c].empty()) add(guidance_sums_[3 + c], schedule_.sets[c]);
    }
    // PM out of this frame's view (IgiFrame::prepare) was neither guided nor evaluated:
    // guidance 0 and no sets, so its channels stay and their means count the frame (a
    // medium that only absorbs is never guided and has none).
    if (stats_.medium_out_of_view && plan_.medium_scatters && guidance_.g[kAisPM].empty()) {
        const std::vector<float> zeros(raw_[kAisSS].size() / 3, 0.0f);
        add(guidance_sums_[kAisPM], zeros);
        add(guidance_sums_[3 + kAisPM], zeros);
    }
    if (!edge_guidance_.empty()) {
        add(guidance_sums_[6], edge_guidance_);
        std::vector<float> samples(edge_schedule_.samples.begin(), edge_schedule_.samples.end());
        for (float& n : samples) n += 1.0f;
        add(guidance_sums_[7], samples);
    }
}

std::string AisFrame::describe() const {
    char buf[480];
    std::snprintf(buf, sizeof buf,
                  "; %s: flagged SS %.1f%%, ID %.1f%%, PM %.1f%%, %zu extra set evaluations, %.1f ms "
                  "(guidance+schedule %.1f, extra sets %.1f, merge %.1f); edges %.1f%%, %zu camera samples, %.1f ms "
                  "(guidance+schedule %.1f, samples %.1f)",
                  settings_.ais_mode == AisMode::AMax ? "ais-max" : "ais", 100 * stats_.flagged[kAisSS],
                  100 * stats_.flagged[kAisID], 100 * stats_.flagged[kAisPM], stats_.ais_items,
                  1e3 * stats_.ais_seconds, 1e3 * stats_.ais_schedule_seconds, 1e3 * stats_.ais_kernel_seconds,
                  1e3 * stats_.ais_merge_seconds, 100 * stats_.edge_flagged, stats_.edge_samples,
                  1e3 * stats_.edge_seconds, 1e3 * stats_.edge_schedule_seconds, 1e3 * stats_.edge_kernel_seconds);
    std::string line = IgiFrame::describe() + buf;
    if (stats_.ais_schedule_kernel_seconds > 0.0 || stats_.edge_schedule_kernel_seconds > 0.0) {
        std::snprintf(buf, sizeof buf, "; of the schedules, their kernels %.1f and %.1f ms",
                      1e3 * stats_.ais_schedule_kernel_seconds, 1e3 * stats_.edge_schedule_kernel_seconds);
        line += buf;
    }
    return line;
}

void AisFrame::add_aov_channels(Image& image, uint32_t frames) const {
    IgiFrame::add_aov_channels(image, frames);
    static const char* names[8] = {"guidance.SS", "guidance.ID", "guidance.PM", "sets.SS",
                                   "sets.ID",     "sets.PM",     "guidance.edge", "samples.edge"};
    const uint32_t bits = effective_components();
    for (int i = 0; i < 6; ++i)
        if (bits & (1u << (i % 3))) append_channels(image, guidance_sums_[i], names[i], 1, frames);
    if (bits & TS_COMPONENT_EDGE)
        for (int i = 6; i < 8; ++i) append_channels(image, guidance_sums_[i], names[i], 1, frames);
}

std::vector<std::vector<double>*> AisFrame::aov_sums() {
    std::vector<std::vector<double>*> sums = IgiFrame::aov_sums();
    for (auto& s : guidance_sums_) sums.push_back(&s);
    return sums;
}

}  // namespace tessera
