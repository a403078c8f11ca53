// The instant cache's gather kernel (KernelId::IcGather) on the Embree backend, 16 records
// at a time through the shared lane gather (kernels/shared/ic_gather.h, ts_ic_gather16):
// the same outputs as the one-record kernel, bit for bit, in SIMD.
#pragma once
#include <cstddef>
#include <vector>

#include "kernels/shared/geometry.h"

namespace tessera {

/// Runs ts_ic_gather_item for items 0 .. count-1 of sv.items (TS_IC_GATHER_WORDS each),
/// 16 items per batch; `out` must hold count × TS_IC_GATHER_FLOATS floats, item order.
/// sv.medium is the scene's medium (the links' transmittance); frame.igi_g_clamp is the
/// bound b.
void ic_gather_lanes(const ts::TsSceneView& sv, const TsFrame& frame, size_t count, std::vector<float>& out);

}  // namespace tessera
