#include "gi/ic_gather.h"

#include <algorithm>
#include <cstring>

#include "kernels/shared/ic_gather.h"

namespace tessera {
namespace {

// The kernels read only igi_g_clamp of the frame.
TsFrame gather_frame(float g_clamp) {
    TsFrame f{};
    f.igi_g_clamp = g_clamp;
    return f;
}

// The pair kernel's output as hit codes (uint bits, one per pair).
void hits_of(const std::vector<float>& out, std::vector<uint32_t>& hits) {
    static_assert(TS_IC_PAIR_FLOATS == 1 && TS_IC_PAIR_HIT == 0, "one hit code per pair");
    hits.resize(out.size());
    if (!out.empty()) std::memcpy(hits.data(), out.data(), out.size() * sizeof(float));
}

}  // namespace

IcGatherSums IcGatherSums::from_output(const float* out) {
    IcGatherSums s;
    auto pair = [&](int at) { return double(out[at]) + double(out[at + 1]); };
    for (int c = 0; c < 3; ++c) s.e[c] = pair(TS_IC_GATHER_SUM + 2 * c);
    s.inv_dist = pair(TS_IC_GATHER_INV_DIST);
    s.seen = static_cast<int64_t>(out[TS_IC_GATHER_SEEN]);
    return s;
}

IcGatherSums& IcGatherSums::operator+=(const IcGatherSums& o) {
    for (int c = 0; c < 3; ++c) e[c] += o.e[c];
    inv_dist += o.inv_dist, seen += o.seen;
    return *this;
}

IcGatherSums& IcGatherSums::operator-=(const IcGatherSums& o) {
    for (int c = 0; c < 3; ++c) e[c] -= o.e[c];
    inv_dist -= o.inv_dist, seen -= o.seen;
    // The count is exact: with no VPL left the sums are exactly 0, not their rounding.
    if (seen <= 0) *this = IcGatherSums{};
    return *this;
}

std::array<float, 3> IcGatherSums::irradiance() const {
    if (seen <= 0) return {0.0f, 0.0f, 0.0f};
    const ts::float3 r = ts::ts_vpl_gather_result_double({std::max(0.0, e[0]), std::max(0.0, e[1]), std::max(0.0, e[2])});
    return {r.x, r.y, r.z};
}

float IcGatherSums::harmonic_mean() const {
    return ts::ts_ic_harmonic_mean(double(seen), inv_dist);
}

void ic_set_record_inputs(Backend& backend, const std::vector<IcRecord>& records, const std::vector<float>& vpls) {
    std::vector<float> surfaces(records.size() * TS_IC_GBUF_FLOATS);
    for (size_t i = 0; i < records.size(); ++i)
        std::memcpy(&surfaces[i * TS_IC_GBUF_FLOATS], records[i].surface.data(), sizeof(float) * TS_IC_GBUF_FLOATS);
    backend.set_input(KernelInput::IcRecordSurfaces, surfaces);
    ic_set_vpl_inputs(backend, vpls);
}

void ic_set_vpl_inputs(Backend& backend, const std::vector<float>& vpls) {
    backend.set_input(KernelInput::Vpls, vpls.empty() ? std::vector<float>(TS_VPL_FLOATS, 0.0f) : vpls);
    backend.set_input(KernelInput::VplSetStart, std::vector<uint32_t>{0u, static_cast<uint32_t>(vpls.size() / TS_VPL_FLOATS)});
}

void ic_pack_visible(const int32_t* row, size_t count, uint32_t* mask, size_t first) {
    // Column first + k; the words the row begins and ends in may hold other columns' bits.
    for (size_t k = 0; k < count; ++k)
        if (row[k] == int32_t(TS_IC_PAIR_VISIBLE)) mask[(first + k) >> 5] |= 1u << ((first + k) & 31u);
}

void ic_trace_pairs(Backend& backend, float g_clamp, const std::vector<uint32_t>& items, std::vector<uint32_t>& hits) {
    std::vector<float> out;
    backend.launch_items(KernelId::IcPair, gather_frame(g_clamp), items, out);
    hits_of(out, hits);
}

void ic_trace_pair_grid(Backend& backend, float g_clamp, uint32_t records, uint32_t first, size_t count,
                        std::vector<uint32_t>& hits) {
    TsFrame f = gather_frame(g_clamp);
    f.ic_pair_grid = records;
    f.ic_pair_first = first;
    std::vector<float> out;
    backend.launch_count(KernelId::IcPair, f, count, out);
    hits_of(out, hits);
}

void ic_gather(Backend& backend, float g_clamp, const std::vector<uint32_t>& items,
               const std::vector<uint32_t>& visibility, std::vector<float>& out) {
    backend.set_input(KernelInput::IcVisibility, visibility);
    backend.launch_items(KernelId::IcGather, gather_frame(g_clamp), items, out);
}

}  // namespace tessera
