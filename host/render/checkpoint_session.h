// The render loop's side of checkpoints (format and validation: render/checkpoint.h).
// A CheckpointSession lives for one render_frame() call: it restores the accumulator on
// --resume, saves a checkpoint every RenderSettings::checkpoint_interval_s seconds, and
// turns SIGINT/SIGTERM into "save, then throw Interrupted".
//
// Signals: while a session with options is alive it holds an InterruptScope
// (render/interrupt.h: the handlers only record the signal; a second one soon after the
// first, or during a checkpoint write, is ignored); after_pass() checks it once per pass.
#pragma once
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "backend/backend.h"
#include "render/accumulator.h"
#include "render/checkpoint.h"
#include "render/interrupt.h"
#include "render/settings.h"
#include "scene/scene.h"

namespace tessera {

/// Checkpointing for one render (the `checkpoint` argument of render_frame).
struct CheckpointOptions {
    std::filesystem::path path;               ///< the checkpoint file (checkpoint_path_for(out))
    BackendKind backend = BackendKind::OpenCL;  ///< part of the run's identity
    bool resume = false;                      ///< continue from `path` (InputError if it is missing)
};

/// Throws InputError "--resume: no checkpoint <path> ..." when `path` does not exist: the
/// render command asks before it prints the scene, a session again before it restores.
void require_checkpoint(const std::filesystem::path& path);

class CheckpointSession {
public:
    /// Does nothing at all (no signal handlers, no files) when `options` is null.
    CheckpointSession(const CheckpointOptions* options, const Scene& scene, const RenderSettings& settings,
                      int width, int height);
    ~CheckpointSession();
    CheckpointSession(const CheckpointSession&) = delete;
    CheckpointSession& operator=(const CheckpointSession&) = delete;

    /// On resume, loads the checkpoint into `acc` and returns its pass count (InputError
    /// if it exceeds the spp target, or see load_checkpoint); otherwise returns 0. The
    /// method's sums wait for keep_method_sums.
    uint32_t restore(Accumulator& acc);

    /// The method's own sums (Integrator::aov_sums), saved with every checkpoint from now
    /// on; on resume first filled from the checkpoint. InputError if the checkpoint holds
    /// a different number of them (a checkpoint of another build's method). The pointers
    /// must outlive the session.
    void keep_method_sums(const std::vector<std::vector<double>*>& sums);

    /// Called after each pass is added. Saves a checkpoint when the interval has run
    /// out, or when a signal arrived, and then throws Interrupted (its message says
    /// where the checkpoint is, or that none was written and why). Does neither once
    /// the spp target is reached.
    void after_pass(const Accumulator& acc);

    /// Saves a checkpoint of `acc` and throws Interrupted, as after_pass() does on a
    /// signal: for a signal that another rank of a distributed render received
    /// (render/pass_exchange.h). Without options it throws Interrupted saying that no
    /// checkpoint is kept.
    [[noreturn]] void interrupt(const Accumulator& acc);

private:
    const CheckpointOptions* options_;
    RunIdentity id_;
    uint32_t spp_ = 0;
    double interval_s_ = 0.0;
    std::chrono::steady_clock::time_point last_save_;
    bool save_failed_ = false;  ///< a periodic save failed (said once; tried again each interval)
    std::optional<InterruptScope> interrupts_;
    MethodSums restored_;                          // from the checkpoint, until kept
    uint32_t restored_version_ = 3;                // its format (2: no method sums)
    bool aovs_ = false;                            // --aov: the method's sums are written
    std::vector<const std::vector<double>*> kept_;  // the integrator's, saved each time
};

}  // namespace tessera
