// The SIMD half of the Embree packet dispatch (embree_packets.cpp): one link (a light
// sample or a VPL) of a sample set against the 16 pixels of a packet at once. The math is
// the shared transport's (ts_light_contribution, ts_vpl_geometry, the gather terms of
// kernels/shared/igi.h and vpl.h), called in loops over the lanes that GCC vectorises; the
// rays go straight into Embree's packet layout. Each lane's sums are bit for bit those of
// the one-ray-at-a-time gather (ts_igi_surface_set): same terms, same order.
//
// The loops vectorise because the shared functions are branch-free and this file is
// built with -fno-trapping-math (CMakeLists.txt says why that changes no value).
#pragma once
#include <cstdint>

#include <embree3/rtcore.h>

#include "backend/embree_tracer.h"
#include "kernels/shared/layout.h"
#include "kernels/shared/medium.h"
#include "kernels/shared/sampling.h"

namespace tessera {

constexpr int kLanes = TS_PACKET_LANES;  // rtcOccluded16: AVX-512 width, two AVX2 halves on this CPU

/// The pixels of a packet as a structure of arrays: the surface fields the links read
/// (positions and origins in scene units, unit normals, pos_scale as in TsSurface), and
/// the running gather sums of TsIgiGather (E_ss and E_id before normalisation, visible
/// light samples). A lane without links holds a stand-in surface (another lane's) so that
/// all its rays are finite; its sums are never read.
struct LaneState {
    alignas(64) float position[3][kLanes], geo_normal[3][kLanes], shading_normal[3][kLanes], origin[3][kLanes];
    alignas(64) float pos_scale[kLanes];
    alignas(64) float ss[3][kLanes], id[3][kLanes];
    alignas(64) uint32_t seen[kLanes];
};

/// Sets lane i's surface and clears its sums.
void lane_set(LaneState& ls, int i, const ts::TsSurface& s);

/// Light sample `sample` against every lane: contributions c (3 × kLanes, RGB rows) and
/// shadow rays written into r (origin, direction, tnear, tfar; the caller sets the other
/// fields). `traced[i]` is -1 where lane i takes part (in[i] = -1) and its ray must be
/// traced (ts_igi_light_link_traced), else 0.
void light_links(const LaneState& ls, const ts::TsLightSample& sample, const int (&in)[kLanes],
                 float (&c)[3][kLanes], int (&traced)[kLanes], RTCRay16& r);

/// Adds the light-sample terms c of the lanes with visible[i] = -1 (0: occluded or not
/// traced) to their E_ss and counts them as seen, with the medium's transmittance along
/// each lane's ray in r.
void light_gather(LaneState& ls, const float (&c)[3][kLanes], const int (&visible)[kLanes], const ts::TsMedium& med,
                  const RTCRay16& r);

/// VPL `vpl` (TS_VPL_FLOATS floats, a copy) against every lane: clamped geometry terms g
/// (ts_vpl_geometry; b the clamp, hg the medium's Henyey–Greenstein g) and shadow rays
/// written into r as for light_links; traced[i] = -1 where in[i] = -1 and g[i] > 0.
void vpl_links(const LaneState& ls, const float (&vpl)[TS_VPL_FLOATS], float b, float hg, const int (&in)[kLanes],
               float (&g)[kLanes], int (&traced)[kLanes], RTCRay16& r);

/// Traces the rays of r whose traced[i] is -1 as one rtcOccluded16 packet (none when no
/// lane is traced), in Embree's coherent mode if `coherent`; visible[i] = -1 for those
/// found unoccluded, 0 for the others. r's other lanes are not read.
void lane_occlusion(const ts::TsTracer& tracer, RTCRay16& r, const int (&traced)[kLanes], bool coherent,
                    int (&visible)[kLanes]);

/// Adds the VPL's terms to E_id of the lanes with visible[i] = -1, as light_gather.
void vpl_gather(LaneState& ls, const float (&vpl)[TS_VPL_FLOATS], const float (&g)[kLanes],
                const int (&visible)[kLanes], const ts::TsMedium& med, const RTCRay16& r);

}  // namespace tessera
