// Scrambled Halton points for the VPL light paths: point i is the same in every frame
// and on every backend, so unchanged light paths come back identical (the correlated
// sampling of IGI, and what temporal instant caching relies on).
#pragma once
#include <cstdint>
#include <vector>

namespace tessera {

/// Halton sequence over the first `dims` primes with random digit scrambling (Kocis &
/// Whiten 1997): dimension d applies one fixed permutation of {0..b-1}, drawn from
/// `seed`, to every digit. The permutation removes the correlation between high
/// dimensions of the plain Halton sequence; being fixed, it keeps the sequence
/// deterministic. Values lie in [0, 1] (floats: 1.0f within 2^-25 of 1). The digits are kernels/shared/halton.h's table,
/// which the light-path kernel reads as the host does (the same numbers, bit for bit).
class ScrambledHalton {
public:
    ScrambledHalton(int dims, uint32_t seed);

    /// Component `dim` (< dims) of point `index` (ts_halton_sample). Throws
    /// std::out_of_range for a bad dim.
    float sample(uint64_t index, int dim) const;

    int dims() const { return static_cast<int>(table_[0]); }

    /// The table of kernels/shared/halton.h: dims, bases, offsets, permutations.
    const std::vector<uint32_t>& table() const { return table_; }

private:
    std::vector<uint32_t> table_;
};

}  // namespace tessera
