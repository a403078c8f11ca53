// Temporary files a process ended by a signal removes on its way out. The atomic writers
// (image/atomic_file.h) fill hidden `.<name>.tmp.XXXXXX` files beside their targets; a
// run ended at once (a second Ctrl-C during a long pass, render/interrupt.h) skips the
// destructors that would remove them, so the signal handler removes them instead, with
// only async-signal-safe calls (unlink). SIGKILL runs no handler: nothing can be done then.
#pragma once
#include <filesystem>

namespace tessera {

/// Registers a temporary file for removal by remove_registered_temporaries() for the
/// object's lifetime (move-only). Best effort: when all kMaxRegisteredTemporaries slots
/// are taken (a --frames run keeps two temporaries per frame until its commit, so one of
/// over 8,191 frames) the file is not registered. The file exists for a moment before it
/// is registered (mkstemp, then this). The path is made absolute at registration, so
/// a later change of working directory does not matter.
class RemovedOnFatalSignal {
public:
    RemovedOnFatalSignal() = default;
    explicit RemovedOnFatalSignal(const std::filesystem::path& temp);
    ~RemovedOnFatalSignal();
    RemovedOnFatalSignal(RemovedOnFatalSignal&& other) noexcept;
    RemovedOnFatalSignal& operator=(RemovedOnFatalSignal&& other) noexcept;
    RemovedOnFatalSignal(const RemovedOnFatalSignal&) = delete;
    RemovedOnFatalSignal& operator=(const RemovedOnFatalSignal&) = delete;

    /// Whether the file is registered (false: default-constructed, moved from, or no slot
    /// was free).
    bool registered() const { return slot_ >= 0; }

private:
    int slot_ = -1;
};

/// Slots for registered temporaries: a --frames run of 8,191 frames (two each) and a
/// checkpoint; 16,384 words (128 KiB of zero pages) cost nothing until used.
inline constexpr int kMaxRegisteredTemporaries = 16384;

/// Unlinks every registered temporary. Async-signal-safe (lock-free compare-and-swaps and
/// unlink): for a signal handler about to end the process. A registration it has taken
/// is not freed; the process is expected to end.
void remove_registered_temporaries() noexcept;

}  // namespace tessera
