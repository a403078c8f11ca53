// The C library's heap, set for a renderer that frees and re-allocates its frame buffers
// (tens of MB at 512²) every pass and frame.
#pragma once
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace tessera {

/// Keeps freed frame buffers in the process for the next pass instead of returning them
/// to the kernel, which would zero-fill them again on first touch: blocks up to 32 MiB come
/// from the heap (glibc's own ceiling for its dynamic threshold; without a fixed value, it
/// moves with the order of frees), and up to 512 MiB of free heap top stays mapped. Why:
/// glibc's defaults turned one allocation pattern change into page faults, 85k -> 188k over
/// an 8-frame animated Cornell box AIS render on PoCL (2-core guest), 0.17 -> 0.20 s a
/// frame; with these settings 53k and 0.175 s (bench/results/tic_host_work.md). Call first
/// in main(); the CLI and every bench/ binary do, so that their timings agree. No effect
/// outside glibc.
inline void keep_frame_memory() {
#if defined(__GLIBC__)
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 512 << 20);
#endif
}

}  // namespace tessera
