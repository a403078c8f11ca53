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

/// Sets flush-to-zero and denormals-are-zero on the calling thread, as Embree asks of
/// every thread that traces rays (denormal slow paths otherwise cost up to 100x).
void set_ftz_daz();

}  // namespace tessera
