// The loop over a batch's 16-item packets that the Embree backend's packet dispatches share.
#pragma once
#include <algorithm>
#include <cstddef>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "bvh/embree_device.h"

namespace tessera {

/// Calls fn(first, lanes) for items [first, first + lanes) of 0 .. n-1, 16 consecutive
/// items a call (fewer in the last), in parallel over TBB; each thread first sets
/// flush-to-zero and denormals-are-zero, as Embree asks (embree_device.h) and as the
/// one-item dispatch does, so results do not depend on the dispatch.
template <class Fn>
void for_each_packet(size_t n, Fn fn) {
    const size_t packets = (n + 15) / 16;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, packets, 16), [&](const tbb::blocked_range<size_t>& r) {
        const FtzDazScope ftz_daz;
        for (size_t q = r.begin(); q < r.end(); ++q) fn(16 * q, std::min<size_t>(16, n - 16 * q));
    });
}

}  // namespace tessera
