// The instant cache's record–VPL work on the backend (docs/instant-caching.md §3, §7, §8):
// launches of the pair kernel (KernelId::IcPair: one shadow ray per record–VPL pair) and
// the gather kernel (KernelId::IcGather: one record's E and harmonic mean distance from
// its visibility row), both shared code in kernels/shared/ic.h. The callers decide which
// pairs and records need work (placement, the temporal update, the rebuild) and build the
// item lists; these functions only set the inputs and launch.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "backend/backend.h"
#include "gi/irradiance_cache.h"
#include "kernels/shared/layout_igi.h"

namespace tessera {

/// The VPLs in `vpls` (TS_VPL_FLOATS each).
inline size_t vpl_count(const std::vector<float>& vpls) { return vpls.size() / TS_VPL_FLOATS; }

/// Sets the inputs both kernels read: the surfaces of `records` (KernelInput::
/// IcRecordSurfaces, TS_IC_GBUF_FLOATS each; items index them) and `vpls`
/// (TS_VPL_FLOATS each) as one sample set (Vpls, VplSetStart = {0, count}). Replaces
/// the igi VPLs: call after the igi kernels of the pass.
void ic_set_record_inputs(Backend& backend, const std::vector<IcRecord>& records, const std::vector<float>& vpls);
/// The VPL inputs alone (Vpls, VplSetStart = {0, count}), ic_set_record_inputs' second
/// half: the pair grid of one path subset reads that subset's VPLs with the records set.
void ic_set_vpl_inputs(Backend& backend, const std::vector<float>& vpls);

/// One launch of the pair kernel over `items` (TS_IC_PAIR_WORDS uints each: record, VPL;
/// layout_ic.h) with geometry-term bound `g_clamp`. `hits` gets one code per item: the first
/// triangle the shadow ray hits, TS_IC_PAIR_VISIBLE (unoccluded) or TS_IC_PAIR_FACING
/// (geometry term 0, no ray traced).
void ic_trace_pairs(Backend& backend, float g_clamp, const std::vector<uint32_t>& items,
                    std::vector<uint32_t>& hits);

/// One launch of the pair kernel over pairs first .. first + count - 1 of the grid of
/// `records` records (the IcPairRecords input, set by the caller) and every VPL: pair g is
/// (record g mod records, VPL g / records), so 16 consecutive pairs share a VPL as the
/// item list's VPL-major order does, without the list. `hits` as ic_trace_pairs.
void ic_trace_pair_grid(Backend& backend, float g_clamp, uint32_t records, uint32_t first, size_t count,
                        std::vector<uint32_t>& hits);

/// Packs the visibility `row` of `count` VPLs, columns first .. first + count − 1 (the
/// host's int32 per pair, kIcVisible where unoccluded; instant_cache.h), into the gather
/// kernel's bit mask over all the set's VPLs (TS_IC_VISIBLE_WORDS(VPLs) uints at `mask`,
/// layout_ic.h): sets the bits of the visible columns, so `mask` must start zeroed.
void ic_pack_visible(const int32_t* row, size_t count, uint32_t* mask, size_t first = 0);

/// A gather's sums (the TS_IC_GATHER_SUM, _INV_DIST and _SEEN outputs, layout_ic.h), in
/// double: Σ C·T·min(G, b) per channel (π E), Σ 1/distance (1 / scene units) and the count
/// of visible VPLs. Sums over disjoint sets of VPLs add, so the temporal update re-sums a
/// record by subtracting the sum over the VPLs that changed and adding their new sum
/// (docs/instant-caching.md §8).
struct IcGatherSums {
    double e[3] = {0.0, 0.0, 0.0};
    double inv_dist = 0.0;
    int64_t seen = 0;
    /// From one item's gather output (TS_IC_GATHER_FLOATS floats): each (hi, lo) pair summed in double.
    static IcGatherSums from_output(const float* out);
    IcGatherSums& operator+=(const IcGatherSums& o);
    IcGatherSums& operator-=(const IcGatherSums& o);
    /// E = irradiance / π as the gather kernel forms it from its sums (shared/vpl.h), 0 with
    /// no VPL visible (rounding in a difference of sums can leave a tiny negative, clamped to 0).
    std::array<float, 3> irradiance() const;
    /// The harmonic mean distance to the visible VPLs (scene units; +inf for none), as the kernel forms it.
    float harmonic_mean() const;
};

/// One launch of the gather kernel over `items` (TS_IC_GATHER_WORDS uints each: record,
/// row of `visibility`; layout_ic.h). `visibility` holds bit-mask rows
/// (TS_IC_VISIBLE_WORDS(VPLs of the set input) uints each, ic_pack_visible). `out` gets
/// TS_IC_GATHER_FLOATS per item: E = irradiance / π, the harmonic mean distance (scene
/// units, +inf when no VPL is visible), then the sums they come from (IcGatherSums).
void ic_gather(Backend& backend, float g_clamp, const std::vector<uint32_t>& items,
               const std::vector<uint32_t>& visibility, std::vector<float>& out);

}  // namespace tessera
