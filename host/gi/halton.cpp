#include "gi/halton.h"

#include <algorithm>
#include <random>
#include <stdexcept>

namespace tessera {
namespace {

std::vector<uint32_t> first_primes(int n) {
    std::vector<uint32_t> p;
    for (uint32_t c = 2; static_cast<int>(p.size()) < n; ++c)
        if (std::all_of(p.begin(), p.end(), [c](uint32_t q) { return c % q != 0; })) p.push_back(c);
    return p;
}

}  // namespace

ScrambledHalton::ScrambledHalton(int dims, uint32_t seed) : bases_(first_primes(dims)) {
    std::mt19937 rng(seed);
    for (uint32_t b : bases_) {
        std::vector<uint32_t> perm(b);
        for (uint32_t i = 0; i < b; ++i) perm[i] = i;
        std::shuffle(perm.begin(), perm.end(), rng);
        perms_.push_back(std::move(perm));
    }
}

double ScrambledHalton::sample(uint64_t index, int dim) const {
    if (dim < 0 || dim >= dims()) throw std::out_of_range("ScrambledHalton: dimension out of range");
    const uint32_t b = bases_[dim];
    const std::vector<uint32_t>& perm = perms_[dim];
    const double inv = 1.0 / b;
    double f = inv, r = 0.0;
    // Every digit position is permuted, the (infinitely many) leading zeros of the index
    // too; positions beyond double precision add nothing, so 64 / log2(b) digits suffice.
    while (f > 1e-17) {
        r += perm[index % b] * f;
        index /= b;
        f *= inv;
    }
    return std::min(r, 0.99999999999999989);
}

}  // namespace tessera
