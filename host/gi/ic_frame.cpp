#include "gi/ic_frame.h"

#include <chrono>

#include "integrators/factory.h"

namespace tessera {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace

void IcFrame::refine(const TsFrame& frame, const std::vector<float>& surf, const std::vector<float>& media) {
    (void)media;
    if (!(frame.igi_components & TS_COMPONENT_ID)) return;
    const auto tc = Clock::now();
    if (plan_.indirect) cache_->indirect(backend_, scene_, frame, surf, frame.igi_g_clamp, raw_[kAisID]);
    stats_.cache_seconds = since(tc);
}

void IcFrame::reconstruct_component(int c) {
    if (c == kAisID)
        final_[c] = raw_[c];
    else
        IgiFrame::reconstruct_component(c);
}

std::string IcFrame::describe() const { return IgiFrame::describe() + "; " + cache_->describe(); }

void IcFrame::report(IntegratorStats& stats) const {
    IgiFrame::report(stats);
    stats.ic = cache_->stats();
}

}  // namespace tessera
