#include "image/fatal_signal_cleanup.h"

#include <signal.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <system_error>

namespace tessera {
namespace {

// Each slot holds a heap copy of a registered path, or null. The handler marks a path it
// removes by setting the pointer's low bit (new[] blocks are at least 8-byte aligned) with
// a compare-and-swap; the owner frees a path only by swapping it for null. Whichever swap
// succeeds decides, so a handler running on another thread never reads a path being
// freed, and a marked slot is never reused. A marked path is never freed (the process is
// ending), yet stays reachable for leak checkers: the marked pointer points into it.
// The second bit says the path is a directory (removed by rmdir, after the files).
std::atomic<std::uintptr_t> g_slots[kMaxRegisteredTemporaries];
constexpr std::uintptr_t kRemovedBit = 1, kDirectoryBit = 2, kFlags = kRemovedBit | kDirectoryBit;
static_assert(alignof(std::max_align_t) >= 4, "new[] leaves the two low bits of a pointer free");
static_assert(std::atomic<std::uintptr_t>::is_always_lock_free);

// At least 4 bytes: a marked pointer (+1, +2 or +3) must still point into the block, or
// LeakSanitizer would not count the path as reachable ("/a" is 3 bytes).
char* copy_of(const std::string& s) {
    char* p = new char[std::max<size_t>(s.size() + 1, 4)];
    std::memcpy(p, s.c_str(), s.size() + 1);
    return p;
}

// The process group of a child tool running now (0: none), killed before the files are
// removed: a tool still running could otherwise write a temporary again after it went.
std::atomic<pid_t> g_child_group{0};
static_assert(std::atomic<pid_t>::is_always_lock_free);

}  // namespace

RemovedOnFatalSignal::RemovedOnFatalSignal(const std::filesystem::path& temp) : RemovedOnFatalSignal(temp, false) {}

RemovedOnFatalSignal RemovedOnFatalSignal::directory(const std::filesystem::path& dir) {
    return RemovedOnFatalSignal(dir, true);
}

RemovedOnFatalSignal::RemovedOnFatalSignal(const std::filesystem::path& temp, bool directory) {
    std::error_code ec;
    const std::filesystem::path absolute = std::filesystem::absolute(temp, ec);
    char* path = copy_of((ec ? temp : absolute).string());
    const std::uintptr_t entry = reinterpret_cast<std::uintptr_t>(path) | (directory ? kDirectoryBit : 0);
    for (int i = 0; i < kMaxRegisteredTemporaries; ++i) {
        std::uintptr_t empty = 0;
        if (g_slots[i].compare_exchange_strong(empty, entry)) {
            slot_ = i;
            return;
        }
    }
    delete[] path;
}

RemovedOnFatalSignal::~RemovedOnFatalSignal() {
    if (slot_ < 0) return;
    std::uintptr_t path = g_slots[slot_].load();
    // Fails only when the handler marked the path: it is the handler's then.
    if (!(path & kRemovedBit) && g_slots[slot_].compare_exchange_strong(path, 0))
        delete[] reinterpret_cast<char*>(path & ~kFlags);
}

RemovedOnFatalSignal::RemovedOnFatalSignal(RemovedOnFatalSignal&& other) noexcept : slot_(other.slot_) {
    other.slot_ = -1;
}

RemovedOnFatalSignal& RemovedOnFatalSignal::operator=(RemovedOnFatalSignal&& other) noexcept {
    if (this != &other) {
        RemovedOnFatalSignal old(std::move(*this));
        slot_ = other.slot_;
        other.slot_ = -1;
    }
    return *this;
}

namespace {

// Stops a child tool's process group as a terminal's Ctrl-C would, SIGINT, so that it can
// clean up (Python removes its temporary directories); whatever of it is left after
// kToolGraceNanoseconds, or ignores SIGINT, is killed. The leader is reaped. Only
// async-signal-safe calls (kill, waitpid, nanosleep).
constexpr long kToolGraceNanoseconds = 2'000'000'000;
constexpr long kToolPollNanoseconds = 10'000'000;

void stop_group(pid_t group) {
    ::kill(-group, SIGINT);
    int status = 0;
    bool ended = false;
    for (long waited = 0; !ended && waited < kToolGraceNanoseconds; waited += kToolPollNanoseconds) {
        const pid_t r = ::waitpid(group, &status, WNOHANG);
        if (r == group || (r < 0 && errno != EINTR)) {
            ended = true;  // reaped (or not ours to wait for)
        } else {
            timespec t{0, kToolPollNanoseconds};
            ::nanosleep(&t, nullptr);
        }
    }
    ::kill(-group, SIGKILL);  // what is left of the group (Octave under Python)
    if (!ended) {
        ::kill(group, SIGKILL);  // a leader that left its group
        while (::waitpid(group, &status, 0) < 0 && errno == EINTR) {
        }
    }
}

}  // namespace

KilledOnFatalSignal::KilledOnFatalSignal(pid_t group) : group_(group) { g_child_group = group; }

KilledOnFatalSignal::~KilledOnFatalSignal() {
    pid_t expected = group_;
    g_child_group.compare_exchange_strong(expected, 0);
}

void remove_registered_temporaries() noexcept {
    // A tool's whole group first (a tool that runs Octave has children of its own), and
    // reaped, so that none of it writes after the files are gone.
    if (const pid_t group = g_child_group.exchange(0); group > 0) stop_group(group);
    // Taking every registration first keeps each path alive while it is used below.
    for (std::atomic<std::uintptr_t>& slot : g_slots) {
        std::uintptr_t path = slot.load();
        if (path != 0 && !(path & kRemovedBit) && slot.compare_exchange_strong(path, path | kRemovedBit) &&
            !(path & kDirectoryBit))
            ::unlink(reinterpret_cast<const char*>(path));
    }
    // A directory empties when the ones inside it go: repeat while one was removed (at
    // most once per level of nesting). rmdir leaves a directory that is not empty.
    for (bool removed = true; removed;) {
        removed = false;
        for (std::atomic<std::uintptr_t>& slot : g_slots) {
            std::uintptr_t path = slot.load();
            if ((path & kFlags) == kFlags && ::rmdir(reinterpret_cast<const char*>(path & ~kFlags)) == 0) {
                removed = true;
                slot.compare_exchange_strong(path, path & ~kDirectoryBit);  // done: not tried again
            }
        }
    }
}

namespace {

// SIGQUIT too (Ctrl-\): it ends the process as well, and would leave the tool running.
constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};
constexpr int kCleanupSignalCount = sizeof kCleanupSignals / sizeof kCleanupSignals[0];
struct sigaction g_old_actions[kCleanupSignalCount];

// One word for the holds and a signal held meanwhile, (holds << 8) | signal, so that the
// handler (on any thread) and the end of the last hold agree by compare-and-swap on
// whether a signal is left to act on: no signal is lost between them.
std::atomic<int> g_hold_state{0};
static_assert(std::atomic<int>::is_always_lock_free);

// In the handler the signal is blocked until it returns, and is delivered then, with its
// default action; from ~SignalsHeld, at once.
void remove_temporaries_and_raise(int sig) {
    remove_registered_temporaries();
    ::signal(sig, SIG_DFL);
    ::raise(sig);
}

extern "C" void remove_temporaries_and_end(int sig) {
    for (int state = g_hold_state.load(); state >> 8 > 0;)
        if (g_hold_state.compare_exchange_weak(state, (state & ~0xff) | sig)) return;  // held: acted on at its end
    remove_temporaries_and_raise(sig);
}

}  // namespace

TemporariesRemovedOnSignal::TemporariesRemovedOnSignal() {
    struct sigaction sa {};
    sa.sa_handler = remove_temporaries_and_end;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;  // a held signal must not fail a commit's system calls
    for (int i = 0; i < kCleanupSignalCount; ++i) {
        // Read first: a signal ignored on entry is never unignored, not even for a moment.
        sigaction(kCleanupSignals[i], nullptr, &g_old_actions[i]);
        if (g_old_actions[i].sa_handler != SIG_IGN) sigaction(kCleanupSignals[i], &sa, nullptr);
    }
}

TemporariesRemovedOnSignal::~TemporariesRemovedOnSignal() {
    for (int i = 0; i < kCleanupSignalCount; ++i) sigaction(kCleanupSignals[i], &g_old_actions[i], nullptr);
}

SignalsHeld::SignalsHeld() { g_hold_state += 1 << 8; }

SignalsHeld::~SignalsHeld() {
    for (int state = g_hold_state.load();;) {
        const int left = (state >> 8) - 1, sig = state & 0xff;
        if (left == 0 && sig != 0) {
            if (g_hold_state.compare_exchange_weak(state, 0)) {
                remove_temporaries_and_raise(sig);
                return;  // only if the signal is blocked on this thread
            }
        } else if (g_hold_state.compare_exchange_weak(state, (left << 8) | sig)) {
            return;
        }
    }
}

}  // namespace tessera
