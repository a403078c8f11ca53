// SIGINT, SIGTERM and SIGHUP (a closed terminal or ssh session) during a `tessera render`
// or `tessera view` run. The handler only records the signal;
// the render loop (CheckpointSession::after_pass) and the command check it and stop
// cleanly: a checkpoint saved, or a message saying why none was.
//
// Signals often come in pairs: `timeout -s INT` and a terminal's Ctrl-C signal the
// process and its whole process group at once. So a further signal is ignored when it
// comes within kInterruptGraceSeconds of the first, or while an InterruptDeferral is
// alive (a checkpoint or the outputs being written). A further signal after that (a pass
// that does not end, a user pressing Ctrl-C again) prints one line saying that no
// checkpoint is written, removes the outputs' temporaries (image/fatal_signal_cleanup.h)
// and ends the process by the signal's default action.
#pragma once

namespace tessera {

/// Seconds after the first signal during which further signals are ignored: longer than
/// the spread of one group delivery, short enough that a second Ctrl-C still works.
inline constexpr double kInterruptGraceSeconds = 2.0;

/// Installs the handlers for its lifetime (the old ones are put back at its end, also by
/// an exception). Scopes nest: only the outermost installs, clears the recorded signal
/// and restores. A SIGINT ignored on entry (`cmd &` in a script) stays ignored, and so
/// does a SIGHUP (nohup).
/// Not thread-safe: create scopes on one thread (the handler itself may run on any).
class InterruptScope {
public:
    InterruptScope();
    ~InterruptScope();
    InterruptScope(const InterruptScope&) = delete;
    InterruptScope& operator=(const InterruptScope&) = delete;
};

/// The first signal received inside the outermost live InterruptScope (SIGINT, SIGTERM or
/// SIGHUP),
/// 0 when none was.
int interrupt_signal();

/// While alive, every further signal is ignored (not only those within the grace time),
/// so writing a checkpoint or committing the outputs is not cut short. Nests.
class InterruptDeferral {
public:
    InterruptDeferral();
    ~InterruptDeferral();
    InterruptDeferral(const InterruptDeferral&) = delete;
    InterruptDeferral& operator=(const InterruptDeferral&) = delete;
};

}  // namespace tessera
