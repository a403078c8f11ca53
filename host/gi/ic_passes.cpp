#include "gi/ic_passes.h"

#include <stdexcept>
#include <string>

namespace tessera {

IcPassCaches::IcPassCaches(const IcSettings& settings, const std::vector<SceneObject>& objects)
    : settings_(settings), objects_(objects) {
    InstantCache check(settings_, objects_);  // throws on bad settings now, not at the first pass
}

InstantCache& IcPassCaches::pass(uint32_t pass) {
    const size_t at = slot(pass);
    if (caches_.size() <= at) caches_.resize(at + 1);
    if (!caches_[at]) caches_[at] = std::make_unique<InstantCache>(settings_, objects_);
    return *caches_[at];
}

const InstantCache& IcPassCaches::pass(uint32_t pass) const {
    const size_t at = slot(pass);
    if (at >= caches_.size() || !caches_[at])
        throw std::out_of_range("ic: no cache for pass " + std::to_string(pass) + " yet");
    return *caches_[at];
}

bool IcPassCaches::after_pass(uint32_t pass) {
    if (!settings_.temporal || pass >= caches_.size()) return false;
    size_t pairs = 0;
    for (const auto& c : caches_)
        if (c) pairs += c->pairs_kept();
    if (pairs <= kKeptPairs) return false;
    caches_[pass].reset();
    return true;
}

size_t IcPassCaches::kept() const {
    size_t n = 0;
    for (const auto& c : caches_) n += c && c->pairs_kept() > 0;
    return n;
}

}  // namespace tessera
