#include "integrators/ic_frame.h"

#include <chrono>

#include "integrators/settings.h"

namespace tessera {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace

void IcFrame::refine(const TsFrame& frame, const std::vector<float>& surf, const std::vector<float>& media) {
    (void)media;
    if (!(frame.igi_components & TS_COMPONENT_ID)) return;
    const auto tc = Clock::now();
    if (plan_.indirect) {
        InstantCache& cache = caches_->pass(frame.pass);
        // Fresh paths are kept for the view as igi keeps its VPLs (docs/instant-caching.md §2).
        IcPathSelection selection;
        ViewPoints view;
        const IcSettings& ic = caches_->settings();
        if (ic.path_importance > 1 && cache.draws_paths()) {
            view = view_points(frame);
            selection = {ic.path_importance, &view, importance_clamp_, ic.view_rays};
        }
        cache.indirect(backend_, scene_, frame, surf, frame.igi_g_clamp, selection, caches_->gbuffer(), cached_,
                       residual_);
        std::vector<float>& id = raw_[kAisID];
        id.resize(cached_.size());
        for (size_t i = 0; i < id.size(); ++i) id[i] = cached_[i] + residual_[i];
        frame_stats_ += cache.stats();
        released_ += caches_->after_pass(frame.pass) ? 1 : 0;
        ++passes_;
    }
    stats_.cache_seconds = since(tc);
}

void IcFrame::reconstruct_component(int c) {
    if (c != kAisID) return IgiFrame::reconstruct_component(c);
    if (!settings_.filter || residual_.size() != raw_[c].size()) {
        final_[c] = raw_[c];
        return;
    }
    // The cache's E is smooth already; the residual is one ray a pixel, so it goes through
    // the discontinuity filter as the interleaved components do (docs/instant-caching.md §9).
    discontinuity_filter(geometry_, settings_.discontinuity, 3, residual_, filtered_);
    final_[c].resize(cached_.size());
    for (size_t i = 0; i < cached_.size(); ++i) final_[c][i] = cached_[i] + filtered_[i];
}

std::string IcFrame::describe() const {
    std::string line = IgiFrame::describe() + "; " + describe_ic(caches_->settings(), frame_stats_, passes_);
    if (caches_->temporal())
        line += "; " + std::to_string(caches_->kept()) + " pass caches kept" +
                (released_ ? " (" + std::to_string(released_) + " released over the memory budget)" : "");
    return line;
}

void IcFrame::report(IntegratorStats& stats) const {
    IgiFrame::report(stats);
    stats.ic = frame_stats_;
}

}  // namespace tessera
