// One Embree device for the process, shared by the BVH builder and the Embree backend.
#pragma once
#include <embree3/rtcore.h>

namespace tessera {

/// The process-wide Embree device, created on first use with
/// `frequency_level=simd256` (without it Embree 3.13 picks BVH4 and 128-bit code on
/// Skylake-SP class Xeons; see docs/ray-tracing.md §2). Errors reported by
/// Embree are thrown as RuntimeError by check_embree().
RTCDevice embree_device();

/// Throws RuntimeError naming `what`, Embree's error code and its message (recorded by
/// the device's error function on this thread) if the device has a pending error.
void check_embree(const char* what);

/// Flush-to-zero and denormals-are-zero on the calling thread for the object's lifetime,
/// as Embree asks of every thread that traces rays (denormal slow paths otherwise cost up
/// to 100x); the thread's previous mode comes back at the end. A parallel loop's body
/// holds one: TBB runs bodies on the calling thread too, and a mode set for good there
/// once leaked into the host code after the kernels (a denormal below an option's minimum
/// of 0 then compared equal to 0 and passed the range check).
class FtzDazScope {
public:
    FtzDazScope();
    ~FtzDazScope();
    FtzDazScope(const FtzDazScope&) = delete;
    FtzDazScope& operator=(const FtzDazScope&) = delete;

private:
    unsigned saved_;  ///< the thread's MXCSR before
};

}  // namespace tessera
