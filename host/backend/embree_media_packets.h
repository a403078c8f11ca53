// Packet dispatch of the igi ray march (the media part of igi frames and of AIS items) on
// the Embree backend: up to 16 marches of one sample set run side by side, and each link
// of a step (its light sample; each VPL of the step's share, the same for every pixel of
// the set) is traced as one rtcOccluded16 packet. The march is the shared
// kernels/shared/igi_march16.h, which the OpenCL CPU kernels run too; every lane's values
// equal ts_igi_media_set's bit for bit (tests/backend/media_packets_test.cpp).
// docs/ray-batches.md §2.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "backend/embree_tracer.h"
#include "kernels/shared/layout.h"

namespace tessera {

/// Up to 16 marches: lane i (i < lanes) marches pixel (px[i], py[i]) for sample set k[i]
/// when on[i]. Lanes of one set share their packets; sets are marched one after another.
struct MarchLanes {
    int lanes = 0;
    std::array<uint32_t, TS_PACKET_LANES> px{}, py{}, k{};
    std::array<bool, TS_PACKET_LANES> on{};
};

/// Runs the marches of `lanes` (ts_igi_media_set) and writes lane i's TS_IGI_MEDIA_FLOATS
/// values to out[i] for the lanes that are on. `coherent`: the lanes' pixels lie close
/// together (Embree's coherent packet mode).
void march_packet(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame,
                  const MarchLanes& lanes, bool coherent, const std::array<float*, TS_PACKET_LANES>& out);

/// Runs ts_igi_media_pixel for every pixel of frame.width × frame.height in packets of a
/// 4×4 block of one sample set's pixels (as igi_surface_packets). `out` must hold
/// width × height × TS_IGI_MEDIA_FLOATS floats, row-major.
void igi_media_packets(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame,
                       std::vector<float>& out);

}  // namespace tessera
