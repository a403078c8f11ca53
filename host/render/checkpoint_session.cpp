#include "render/checkpoint_session.h"

#include <system_error>

#include "util/error.h"

namespace tessera {
namespace {

volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_signal(int sig) {
    if (g_signal) {  // second signal: give up on a clean stop
        std::signal(sig, SIG_DFL);
        std::raise(sig);
        return;
    }
    g_signal = sig;
}

}  // namespace

CheckpointSession::CheckpointSession(const CheckpointOptions* options, const Scene& scene,
                                     const RenderSettings& settings, int width, int height)
    : options_(options) {
    if (!options_) return;
    id_ = make_run_identity(scene, settings, width, height, options_->backend);
    spp_ = settings.spp;
    interval_s_ = settings.checkpoint_interval_s;
    last_save_ = std::chrono::steady_clock::now();
    g_signal = 0;
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    sigaction(SIGINT, &sa, &old_int_);
    sigaction(SIGTERM, &sa, &old_term_);
    // A SIGINT ignored on entry (nohup, `cmd &` in a script) stays ignored.
    if (old_int_.sa_handler == SIG_IGN) sigaction(SIGINT, &old_int_, nullptr);
}

CheckpointSession::~CheckpointSession() {
    if (!options_) return;
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
}

uint32_t CheckpointSession::restore(Accumulator& acc) {
    if (!options_ || !options_->resume) return 0;
    std::error_code ec;
    if (!std::filesystem::exists(options_->path, ec))
        throw InputError("--resume: no checkpoint " + options_->path.string() +
                         " (it is written beside --out when a render is interrupted)");
    const uint32_t passes = load_checkpoint(options_->path, id_, acc);
    if (passes > spp_)
        throw InputError("checkpoint " + options_->path.string() + " already holds " + std::to_string(passes) +
                         " passes, more than --spp " + std::to_string(spp_));
    return passes;
}

void CheckpointSession::after_pass(const Accumulator& acc) {
    if (!options_ || acc.passes() >= spp_) return;
    const auto now = std::chrono::steady_clock::now();
    const bool interrupted = g_signal != 0;
    if (interrupted || (interval_s_ > 0 && std::chrono::duration<double>(now - last_save_).count() >= interval_s_)) {
        save_checkpoint(options_->path, id_, spp_, acc);
        last_save_ = std::chrono::steady_clock::now();
    }
    if (interrupted) throw Interrupted(acc.passes(), spp_, options_->path.string());
}

}  // namespace tessera
