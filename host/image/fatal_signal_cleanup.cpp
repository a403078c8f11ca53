#include "image/fatal_signal_cleanup.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
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

char* copy_of(const std::string& s) {
    char* p = new char[s.size() + 1];
    std::memcpy(p, s.c_str(), s.size() + 1);
    return p;
}

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

void remove_registered_temporaries() noexcept {
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

constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP};
struct sigaction g_old_actions[3];

extern "C" void remove_temporaries_and_end(int sig) {
    remove_registered_temporaries();
    ::signal(sig, SIG_DFL);
    ::raise(sig);
}

}  // namespace

TemporariesRemovedOnSignal::TemporariesRemovedOnSignal() {
    struct sigaction sa {};
    sa.sa_handler = remove_temporaries_and_end;
    sigemptyset(&sa.sa_mask);
    for (int i = 0; i < 3; ++i) {
        sigaction(kCleanupSignals[i], &sa, &g_old_actions[i]);
        if (g_old_actions[i].sa_handler == SIG_IGN) sigaction(kCleanupSignals[i], &g_old_actions[i], nullptr);
    }
}

TemporariesRemovedOnSignal::~TemporariesRemovedOnSignal() {
    for (int i = 0; i < 3; ++i) sigaction(kCleanupSignals[i], &g_old_actions[i], nullptr);
}

}  // namespace tessera
