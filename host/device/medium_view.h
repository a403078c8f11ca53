// Whether the camera can see the medium this frame: the per-frame half of "simulate only
// what the scene calls for" (docs/igi.md §1). The effect plan decides at load that a scene
// has a medium; a box of fog out of view still has the igi family's ray march cost a
// camera ray per pixel and the PM filter, though every pixel's in-scattered light is 0.
#pragma once

#include "kernels/shared/frame.h"
#include "kernels/shared/medium.h"

namespace tessera {

/// False only where no camera ray of `frame` can meet the medium: no ray
/// ts_camera_ray(frame, x, y, jx, jy) for any pixel (x, y) and any jitter (jx, jy) in
/// [0, 1]², followed from cam_pos over t ≥ 0, passes ts_medium_clip. Every pixel's ray
/// march then returns in-scattered radiance 0 and transmittance 1 exactly
/// (ts_igi_march_end), so the march can be skipped with the same image bits.
///
/// The test, in double: the image's cone (apex cam_pos, edges forward ± right ± up)
/// against the medium's box by separating axes: the box's 3 face normals, the cone's 4
/// face normals and the 12 cross products of their edges. It is exact for the cone, so it
/// answers true only where some ray could meet the box. Margins keep it safe under the
/// kernels' float rounding: the box grows by 1e-4 of the largest absolute coordinate of
/// the box and the camera (ts_medium_misses_box's margin, far above the slab test's few
/// ulps), and the cone widens by 1e-5 of (1 + |right| + |up|) in each of its image
/// coordinates, ten times the rounding of a camera ray's direction (its sum and its
/// normalisation, a few ulps of those lengths).
///
/// True for a medium filling space (unbounded) and for NaN or infinite inputs; false
/// without a medium (`present` 0). No errors.
bool camera_may_meet_medium(const TsFrame& frame, const ts::TsMedium& medium);

}  // namespace tessera
