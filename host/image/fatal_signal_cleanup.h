// Temporary files a process ended by a signal removes on its way out. The atomic writers
// (image/atomic_file.h) fill hidden `.<name>.tmp.XXXXXX` files beside their targets; a
// run ended at once (a second Ctrl-C during a long pass, render/interrupt.h) skips the
// destructors that would remove them, so the signal handler removes them instead, with
// only async-signal-safe calls (unlink). SIGKILL runs no handler: nothing can be done then.
#pragma once
#include <sys/types.h>

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
    /// Registers a directory the run made: removed (rmdir) only when empty once the
    /// registered files are gone, so one that an output landed in, or that holds anything
    /// else, stays.
    static RemovedOnFatalSignal directory(const std::filesystem::path& dir);
    ~RemovedOnFatalSignal();
    RemovedOnFatalSignal(RemovedOnFatalSignal&& other) noexcept;
    RemovedOnFatalSignal& operator=(RemovedOnFatalSignal&& other) noexcept;
    RemovedOnFatalSignal(const RemovedOnFatalSignal&) = delete;
    RemovedOnFatalSignal& operator=(const RemovedOnFatalSignal&) = delete;

    /// Whether the file is registered (false: default-constructed, moved from, or no slot
    /// was free).
    bool registered() const { return slot_ >= 0; }

private:
    RemovedOnFatalSignal(const std::filesystem::path& path, bool directory);
    int slot_ = -1;
};

/// Slots for registered temporaries: a --frames run of 8,191 frames (two each) and a
/// checkpoint; 16,384 words (128 KiB of zero pages) cost nothing until used.
inline constexpr int kMaxRegisteredTemporaries = 16384;

/// Stops the registered child tool's group (KilledOnFatalSignal; up to 2 s), unlinks every
/// registered temporary, then removes the registered directories that are empty
/// (innermost first, whatever the order of registration). Async-signal-safe
/// (lock-free compare-and-swaps, unlink, rmdir): for a signal handler about to end the
/// process. A registration it has taken is not freed; the process is expected to end.
void remove_registered_temporaries() noexcept;

/// For a command with no clean stop of its own (`tessera compare`): while alive, SIGINT,
/// SIGTERM, SIGHUP and SIGQUIT stop the registered child tool (KilledOnFatalSignal),
/// remove the registered temporaries and then end the process by the signal's default
/// action, so an interrupted run leaves none of its files behind. A signal ignored on
/// entry (nohup, `cmd &` in a script) stays ignored; the old handlers are put back at its
/// end. Does not nest. Not for use inside an InterruptScope (render/interrupt.h), which
/// removes them itself on a second signal. Not thread-safe: create it on one thread.
/// (Ctrl-Z stops this process, not a tool in its own group: the tool runs on meanwhile.)
class TemporariesRemovedOnSignal {
public:
    TemporariesRemovedOnSignal();
    ~TemporariesRemovedOnSignal();
    TemporariesRemovedOnSignal(const TemporariesRemovedOnSignal&) = delete;
    TemporariesRemovedOnSignal& operator=(const TemporariesRemovedOnSignal&) = delete;
};

/// While alive, a signal that TemporariesRemovedOnSignal's handler would end the process
/// on is held, and acted on when the last SignalsHeld ends: for a commit of several
/// outputs (CommitGroup::commit), which a signal must not cut in half. Nests.
class SignalsHeld {
public:
    SignalsHeld();
    ~SignalsHeld();
    SignalsHeld(const SignalsHeld&) = delete;
    SignalsHeld& operator=(const SignalsHeld&) = delete;
};

/// Registers a child process that leads its own process group (a metric tool spawned by
/// `compare`) for the lifetime of the object: remove_registered_temporaries() stops the
/// group before it removes any file (SIGINT, as a terminal's Ctrl-C, so that the tool can
/// clean up its own temporaries; SIGKILL for what is left after 2 s) and reaps the child,
/// so that the tool does not write a temporary again after it was removed. One at a time
/// (a later registration replaces an earlier one).
class KilledOnFatalSignal {
public:
    explicit KilledOnFatalSignal(pid_t group);
    ~KilledOnFatalSignal();
    KilledOnFatalSignal(const KilledOnFatalSignal&) = delete;
    KilledOnFatalSignal& operator=(const KilledOnFatalSignal&) = delete;

private:
    pid_t group_;
};

}  // namespace tessera
