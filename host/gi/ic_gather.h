// The instant cache's record–VPL work on the backend (docs/instant-caching.md §3, §7, §8):
// launches of the pair kernel (KernelId::IcPair: one shadow ray per record–VPL pair) and
// the gather kernel (KernelId::IcGather: one record's E and harmonic mean distance from
// its visibility row), both shared code in kernels/shared/ic.h. The callers decide which
// pairs and records need work (placement, the temporal update, the rebuild) and build the
// item lists; these functions only set the inputs and launch.
#pragma once
#include <cstdint>
#include <vector>

#include "backend/backend.h"
#include "gi/irradiance_cache.h"

namespace tessera {

/// Sets the inputs both kernels read: the surfaces of `records` (KernelInput::
/// IcRecordSurfaces, TS_IC_GBUF_FLOATS each; items index them) and `vpls`
/// (TS_VPL_FLOATS each) as one sample set (Vpls, VplSetStart = {0, count}). Replaces
/// the igi VPLs: call after the igi kernels of the pass.
void ic_set_record_inputs(Backend& backend, const std::vector<IcRecord>& records, const std::vector<float>& vpls);

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

/// Packs the visibility `row` of `count` VPLs (the host's int32 per pair, kIcVisible where
/// unoccluded; instant_cache.h) into the gather kernel's bit mask: TS_IC_VISIBLE_WORDS(count)
/// uints at `mask` (layout_ic.h).
void ic_pack_visible(const int32_t* row, size_t count, uint32_t* mask);

/// One launch of the gather kernel over `items` (TS_IC_GATHER_WORDS uints each: record,
/// row of `visibility`; layout_ic.h). `visibility` holds bit-mask rows
/// (TS_IC_VISIBLE_WORDS(VPLs of the set input) uints each, ic_pack_visible). `out` gets
/// TS_IC_GATHER_FLOATS per item: E = irradiance / π, then the harmonic mean distance
/// (scene units, +inf when no VPL is visible).
void ic_gather(Backend& backend, float g_clamp, const std::vector<uint32_t>& items,
               const std::vector<uint32_t>& visibility, std::vector<float>& out);

}  // namespace tessera
