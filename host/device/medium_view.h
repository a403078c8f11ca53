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
/// face normals and the 12 cross products of their edges. It is exact for the cone: it
/// answers true where some direction of the cone meets the box or comes within the
/// margins. The margins keep it safe under the kernels' float rounding: the box grows by
/// 1e-4 of the largest absolute coordinate of the box and the camera
/// (ts_medium_misses_box's margin, far above the slab test's few ulps), and the cone's
/// edges move out by 1e-5 of |forward| + |right| + |up| (a length in direction space),
/// ten times the rounding of a camera ray's direction (its sum and its normalisation, a
/// few ulps of those lengths).
///
/// True for a medium filling space (unbounded), for NaN or infinite inputs and for a view
/// wider than ~179°; false without a medium (`present` 0). A box given max before min is
/// read as the swapped one, as the slab test reads it. No errors.
bool camera_may_meet_medium(const TsFrame& frame, const ts::TsMedium& medium);

}  // namespace tessera
