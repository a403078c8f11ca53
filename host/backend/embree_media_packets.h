// Packet dispatch of the igi ray march's media pass on the Embree backend: up to 16 marches
// of one sample set run side by side, and each link of a step (its light sample; each VPL
// of the step's share, the same for every pixel of the set) is traced as one
// rtcOccluded16 packet. The march is the shared kernels/shared/igi_march16.h, which the
// OpenCL CPU kernels run too (and embree_packets.cpp for the media part of AIS items);
// every lane's values equal ts_igi_media_set's bit for bit
// (tests/backend/media_packets_test.cpp). docs/ray-batches.md §2.
#pragma once
#include <vector>

#include "backend/embree_tracer.h"
#include "kernels/shared/frame.h"
#include "kernels/shared/layout_igi.h"

namespace tessera {

/// Runs ts_igi_media_pixel for every pixel of frame.width × frame.height in packets of a
/// 4×4 block of one sample set's pixels (as igi_surface_packets), in Embree's coherent
/// packet mode. `out` must hold width × height × TS_IGI_MEDIA_FLOATS floats, row-major.
void igi_media_packets(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame,
                       std::vector<float>& out);

}  // namespace tessera
