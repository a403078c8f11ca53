// FNV-1a, 64 bit (Fowler, Noll, Vo): the one hash of checkpoints, run identities and the
// OpenCL program cache. Not cryptographic: it finds damage and tells keys apart; it does
// not resist a forger (the program cache's privacy comes from the directory's owner).
#pragma once
#include <cstddef>
#include <cstdint>

namespace tessera {

/// 64-bit FNV-1a of `size` bytes, continuing from `h` (the offset basis by default).
inline uint64_t fnv1a64(const void* data, std::size_t size, uint64_t h = 0xcbf29ce484222325ull) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
        h ^= p[i];
        h *= 0x100000001b3ull;
    }
    return h;
}

}  // namespace tessera
