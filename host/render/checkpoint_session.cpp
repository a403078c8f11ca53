#include "render/checkpoint_session.h"

#include <cstdio>
#include <system_error>

#include "render/interrupt.h"
#include "util/error.h"

namespace tessera {
CheckpointSession::CheckpointSession(const CheckpointOptions* options, const Scene& scene,
                                     const RenderSettings& settings, int width, int height)
    : options_(options) {
    if (!options_) return;
    id_ = make_run_identity(scene, settings, width, height, options_->backend);
    spp_ = settings.spp;
    aovs_ = settings.aovs;
    interval_s_ = settings.checkpoint_interval_s;
    last_save_ = std::chrono::steady_clock::now();
    interrupts_.emplace();
}

CheckpointSession::~CheckpointSession() = default;

void require_checkpoint(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        throw InputError("--resume: no checkpoint " + path.string() +
                         " (it is written beside --out when a render is interrupted)");
}

uint32_t CheckpointSession::restore(Accumulator& acc) {
    if (!options_ || !options_->resume) return 0;
    require_checkpoint(options_->path);
    const uint32_t passes = load_checkpoint(options_->path, id_, acc, &restored_, &restored_version_);
    if (passes > spp_)
        throw InputError("checkpoint " + options_->path.string() + " already holds " + std::to_string(passes) +
                         " passes, more than --spp " + std::to_string(spp_));
    return passes;
}

void CheckpointSession::keep_method_sums(const std::vector<std::vector<double>*>& sums) {
    if (!options_) return;
    // A format-2 checkpoint has no method sums: enough where the method keeps none
    // without --aov (its sums stay empty), not where the resumed channels would need them.
    const bool older_without_sums = restored_version_ < 3 && restored_.empty() && !aovs_;
    if (options_->resume && restored_version_ < 3 && !older_without_sums && !sums.empty())
        throw InputError("checkpoint " + options_->path.string() + " has format 2, which does not hold the method's "
                         "--aov sums; delete it to render from the start");
    if (options_->resume && restored_.size() != sums.size() && !older_without_sums)
        throw InputError("checkpoint " + options_->path.string() + " holds " + std::to_string(restored_.size()) +
                         " method sum arrays, this method keeps " + std::to_string(sums.size()));
    for (size_t k = 0; k < restored_.size(); ++k) *sums[k] = std::move(restored_[k]);
    restored_.clear();
    kept_.assign(sums.begin(), sums.end());
}

void CheckpointSession::after_pass(const Accumulator& acc) {
    if (!options_ || acc.passes() >= spp_) return;
    const auto now = std::chrono::steady_clock::now();
    const bool interrupted = interrupt_signal() != 0;
    if (interrupted) interrupt(acc);
    if (interval_s_ > 0 && std::chrono::duration<double>(now - last_save_).count() >= interval_s_) {
        const InterruptDeferral defer;
        try {
            save_checkpoint(options_->path, id_, spp_, acc, kept_);
        } catch (const RuntimeError& e) {
            // A checkpoint is insurance, not the result: a full disk (a checkpoint is ~4x the
            // EXR) must not end a render whose image would still fit. Said once; tried again
            // at the next interval.
            if (!save_failed_)
                std::fprintf(stderr, "tessera: note: %s; the render goes on (an interrupt now may keep no "
                                     "checkpoint)\n", e.what());
            save_failed_ = true;
        }
        last_save_ = std::chrono::steady_clock::now();
    }
}

void CheckpointSession::interrupt(const Accumulator& acc) {
    if (!options_)
        throw Interrupted("interrupted after " + std::to_string(acc.passes()) +
                          " passes; no checkpoint written (this render keeps none)");
    const InterruptDeferral defer;  // a second signal must not cut the checkpoint short
    try {
        save_checkpoint(options_->path, id_, spp_, acc, kept_);
    } catch (const std::exception& e) {
        throw Interrupted("interrupted after " + std::to_string(acc.passes()) + " of " + std::to_string(spp_) +
                          " spp; no checkpoint written: " + e.what());
    }
    throw Interrupted(acc.passes(), spp_, options_->path.string());
}

}  // namespace tessera
