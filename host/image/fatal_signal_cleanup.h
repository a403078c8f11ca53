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
/// are taken (a --frames run of over 2,000 frames keeps two temporaries per frame until
/// its commit) the file is not registered. The path is made absolute at registration, so
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

/// Slots for registered temporaries: 8 per frame would do for 512 frames; 4,096 pointers
/// (32 KiB) cost nothing until used.
inline constexpr int kMaxRegisteredTemporaries = 4096;

/// Unlinks every registered temporary. Async-signal-safe (atomic exchanges and unlink):
/// for a signal handler about to end the process. A registration it has taken is not
/// freed; the process is expected to end.
void remove_registered_temporaries() noexcept;

}  // namespace tessera
