// The render loop's side of checkpoints (format and validation: render/checkpoint.h).
// A CheckpointSession lives for one render_frame() call: it restores the accumulator on
// --resume, saves a checkpoint every RenderSettings::checkpoint_interval_s seconds, and
// turns SIGINT/SIGTERM into "save, then throw Interrupted".
//
// Signals: while a session with options is alive, SIGINT and SIGTERM handlers only set
// a volatile std::sig_atomic_t flag; after_pass() checks it once per pass. A second
// signal before that check restores the default action and re-raises, so a stuck pass
// can still be killed. A SIGINT that was ignored on entry (nohup, `cmd &` in a
// non-interactive shell) is left ignored. The previous handlers are put back when the session ends (also
// when it ends by an exception).
#pragma once
#include <chrono>
#include <csignal>
#include <cstdint>
#include <filesystem>

#include "backend/backend.h"
#include "render/accumulator.h"
#include "render/checkpoint.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace tessera {

/// Checkpointing for one render (the `checkpoint` argument of render_frame).
struct CheckpointOptions {
    std::filesystem::path path;               ///< the checkpoint file (checkpoint_path_for(out))
    BackendKind backend = BackendKind::OpenCL;  ///< part of the run's identity
    bool resume = false;                      ///< continue from `path` (InputError if it is missing)
};

class CheckpointSession {
public:
    /// Does nothing at all (no signal handlers, no files) when `options` is null.
    CheckpointSession(const CheckpointOptions* options, const Scene& scene, const RenderSettings& settings,
                      int width, int height);
    ~CheckpointSession();
    CheckpointSession(const CheckpointSession&) = delete;
    CheckpointSession& operator=(const CheckpointSession&) = delete;

    /// On resume, loads the checkpoint into `acc` and returns its pass count (InputError
    /// if it exceeds the spp target, or see load_checkpoint); otherwise returns 0.
    uint32_t restore(Accumulator& acc);

    /// Called after each pass is added. Saves a checkpoint when the interval has run
    /// out, or when a signal arrived, and then throws Interrupted. Does neither once
    /// the spp target is reached.
    void after_pass(const Accumulator& acc);

private:
    const CheckpointOptions* options_;
    RunIdentity id_;
    uint32_t spp_ = 0;
    double interval_s_ = 0.0;
    std::chrono::steady_clock::time_point last_save_;
    struct sigaction old_int_{}, old_term_{};
};

}  // namespace tessera
