#include "image/fatal_signal_cleanup.h"

#include <unistd.h>

#include <atomic>
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
std::atomic<std::uintptr_t> g_slots[kMaxRegisteredTemporaries];
constexpr std::uintptr_t kRemovedBit = 1;
static_assert(std::atomic<std::uintptr_t>::is_always_lock_free);

char* copy_of(const std::string& s) {
    char* p = new char[s.size() + 1];
    std::memcpy(p, s.c_str(), s.size() + 1);
    return p;
}

}  // namespace

RemovedOnFatalSignal::RemovedOnFatalSignal(const std::filesystem::path& temp) {
    std::error_code ec;
    const std::filesystem::path absolute = std::filesystem::absolute(temp, ec);
    char* path = copy_of((ec ? temp : absolute).string());
    for (int i = 0; i < kMaxRegisteredTemporaries; ++i) {
        std::uintptr_t empty = 0;
        if (g_slots[i].compare_exchange_strong(empty, reinterpret_cast<std::uintptr_t>(path))) {
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
        delete[] reinterpret_cast<char*>(path);
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
    for (std::atomic<std::uintptr_t>& slot : g_slots) {
        std::uintptr_t path = slot.load();
        if (path != 0 && !(path & kRemovedBit) && slot.compare_exchange_strong(path, path | kRemovedBit))
            ::unlink(reinterpret_cast<const char*>(path));
    }
}

}  // namespace tessera
