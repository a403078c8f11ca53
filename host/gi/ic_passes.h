// The instant caches of the passes of a frame (docs/instant-caching.md §2): pass p gathers
// from its own light paths (path block p) and its own records, so that passes accumulate
// towards the path-traced image as igi's and ic's do. ic makes pass p's cache afresh every
// pass; tic keeps one cache per pass index across the frames of a sequence and updates it
// (§8), so tic's frame 0 is ic's for any number of passes and every later frame equals a
// rebuild pass by pass.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "gi/instant_cache.h"
#include "scene/scene.h"

namespace tessera {

class IcPassCaches {
public:
    /// `settings.temporal` chooses tic (caches kept per pass) or ic (one, made afresh).
    /// `objects` are the scene's (stable over an animation).
    IcPassCaches(const IcSettings& settings, const std::vector<SceneObject>& objects);

    /// The cache that serves pass `pass` (made on first use): tic's own cache of that
    /// pass, or ic's single cache, which InstantCache::indirect rebuilds every call.
    InstantCache& pass(uint32_t pass);
    /// The cache of a pass that has run; throws std::out_of_range otherwise.
    const InstantCache& pass(uint32_t pass) const;

    /// After `pass`'s InstantCache::indirect: tic releases that pass's cache when the caches
    /// kept hold more than kKeptPairs record–VPL visibilities. A released pass is built
    /// afresh on its next frame, the records the update would have given (§8), at a
    /// rebuild's cost. Returns true when it released it.
    bool after_pass(uint32_t pass);

    /// Scratch for the cache G-buffer, shared by the passes (15 MB at 512²).
    std::vector<float>& gbuffer() { return gbuffer_; }
    bool temporal() const { return settings_.temporal; }
    const IcSettings& settings() const { return settings_; }
    /// Caches holding records now.
    size_t kept() const;

    /// Visibilities (4 bytes each) the kept caches may hold in all: 1 GiB, 36 passes of a
    /// 512² Cornell box at the defaults (7.4M pairs a pass). Beyond it a pass's memory
    /// would outgrow what its kept update saves.
    static constexpr size_t kKeptPairs = size_t(1) << 28;

private:
    size_t slot(uint32_t pass) const { return settings_.temporal ? pass : 0; }

    IcSettings settings_;
    std::vector<SceneObject> objects_;
    std::vector<std::unique_ptr<InstantCache>> caches_;  // tic: index = pass; ic: one
    std::vector<float> gbuffer_;
};

}  // namespace tessera
