#include "gi/halton.h"

#include <algorithm>
#include <random>
#include <stdexcept>

#include "kernels/shared/halton.h"

namespace tessera {
namespace {

std::vector<uint32_t> first_primes(int n) {
    std::vector<uint32_t> p;
    for (uint32_t c = 2; static_cast<int>(p.size()) < n; ++c)
        if (std::all_of(p.begin(), p.end(), [c](uint32_t q) { return c % q != 0; })) p.push_back(c);
    return p;
}

}  // namespace

ScrambledHalton::ScrambledHalton(int dims, uint32_t seed) {
    const std::vector<uint32_t> bases = first_primes(dims);
    table_.push_back(static_cast<uint32_t>(dims));
    table_.insert(table_.end(), bases.begin(), bases.end());
    table_.resize(1 + 2 * size_t(dims));
    std::mt19937 rng(seed);
    for (int d = 0; d < dims; ++d) {
        const uint32_t b = bases[d];
        std::vector<uint32_t> perm(b);
        for (uint32_t i = 0; i < b; ++i) perm[i] = i;
        std::shuffle(perm.begin(), perm.end(), rng);
        table_[1 + dims + d] = static_cast<uint32_t>(table_.size());
        table_.insert(table_.end(), perm.begin(), perm.end());
    }
}

float ScrambledHalton::sample(uint64_t index, int dim) const {
    if (dim < 0 || dim >= dims()) throw std::out_of_range("ScrambledHalton: dimension out of range");
    return ts::ts_halton_sample(table_.data(), index, static_cast<uint32_t>(dim));
}

}  // namespace tessera
