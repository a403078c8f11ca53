#include "render/interrupt.h"

#include <signal.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>

#include "image/fatal_signal_cleanup.h"

namespace tessera {
namespace {

// Read and written by the handler, which may run on any thread: lock-free atomics only.
std::atomic<int> g_signal{0};
std::atomic<int64_t> g_first_ns{0};  // CLOCK_MONOTONIC time of the first signal
std::atomic<int> g_deferrals{0};
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<int64_t>::is_always_lock_free);

int g_depth = 0;  // live InterruptScopes (one thread)
struct sigaction g_old_int {}, g_old_term {}, g_old_hup {};

int64_t monotonic_ns() {
    timespec t{};
    ::clock_gettime(CLOCK_MONOTONIC, &t);  // async-signal-safe
    return int64_t(t.tv_sec) * 1000000000 + t.tv_nsec;
}

extern "C" void on_signal(int sig) {
    const int64_t now = monotonic_ns();
    int none = 0;
    if (g_signal.compare_exchange_strong(none, sig)) {
        g_first_ns = now;
        return;
    }
    if (g_deferrals > 0 || now - g_first_ns < int64_t(kInterruptGraceSeconds * 1e9)) return;
    static const char msg[] = "\ntessera: interrupted again: stopping now, no checkpoint written\n";
    [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, msg, sizeof msg - 1);
    remove_registered_temporaries();  // the outputs' unfinished temporaries: no destructor runs now
    ::signal(sig, SIG_DFL);
    ::raise(sig);
}

}  // namespace

InterruptScope::InterruptScope() {
    if (g_depth++ > 0) return;
    g_signal = 0;
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    // The old actions read first: an ignored SIGINT (`cmd &` in a script) or SIGHUP (nohup)
    // is never unignored, not even for a moment.
    sigaction(SIGINT, nullptr, &g_old_int);
    sigaction(SIGTERM, nullptr, &g_old_term);
    sigaction(SIGHUP, nullptr, &g_old_hup);
    if (g_old_int.sa_handler != SIG_IGN) sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
    if (g_old_hup.sa_handler != SIG_IGN) sigaction(SIGHUP, &sa, nullptr);
}

InterruptScope::~InterruptScope() {
    if (--g_depth > 0) return;
    sigaction(SIGINT, &g_old_int, nullptr);
    sigaction(SIGTERM, &g_old_term, nullptr);
    sigaction(SIGHUP, &g_old_hup, nullptr);
}

int interrupt_signal() { return g_signal; }

InterruptDeferral::InterruptDeferral() { ++g_deferrals; }
InterruptDeferral::~InterruptDeferral() { --g_deferrals; }

}  // namespace tessera
