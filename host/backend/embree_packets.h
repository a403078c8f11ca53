// Packet dispatch of the igi surface pass and the AIS extra items on the Embree backend:
// the shadow rays of 16 pixels of one interleave set go to Embree as one rtcOccluded16
// packet per link (the same light sample or VPL for all 16), the transport is the shared
// link/gather code of kernels/shared/igi.h. docs/ray-batches.md gives the design; the
// images equal those of the single-ray dispatch (tests/backend/embree_packets_test.cpp).
#pragma once
#include <cstddef>
#include <vector>

#include "backend/embree_tracer.h"
#include "kernels/shared/frame.h"
#include "kernels/shared/layout_igi.h"

namespace tessera {

/// Runs ts_igi_surface_pixel for every pixel of frame.width × frame.height, in packets:
/// each packet is a 4×4 block of one sample set's pixels (pixels n apart on screen for
/// tile n). `out` must hold width × height × TS_IGI_SURF_FLOATS floats, row-major.
void igi_surface_packets(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame,
                         std::vector<float>& out);

/// Runs ts_ais_extra_item for items 0 .. count-1 of sv.items, 16 consecutive items per
/// packet (the host lists items grouped by sample set). `out` must hold
/// count × TS_AIS_ITEM_FLOATS floats, item order.
void ais_item_packets(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame, size_t count,
                      std::vector<float>& out);

}  // namespace tessera
