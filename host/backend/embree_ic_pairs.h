// The instant cache's pair kernel (KernelId::IcPair) on the Embree backend, 16 record–VPL
// pairs per rtcOccluded16 packet (ts_trace_any_hit16): the same pairs blocked as the
// one-pair kernel, each with a triangle on its ray (not always the one-pair kernel's:
// any-hit queries stop at the first triangle their walk finds).
#pragma once
#include <cstddef>
#include <vector>

#include "backend/embree_tracer.h"

namespace tessera {

/// Runs ts_ic_pair_item for items 0 .. count-1 of sv.items (TS_IC_PAIR_WORDS each), 16
/// consecutive items per packet; `out` must hold count × TS_IC_PAIR_FLOATS floats, item
/// order. A packet whose pairs share one VPL (placement lists them so, a 4×4 block of
/// records per VPL) goes in Embree's coherent mode, others (a record's re-traced pairs)
/// in incoherent mode.
void ic_pair_packets(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame, size_t count,
                     std::vector<float>& out);

}  // namespace tessera
