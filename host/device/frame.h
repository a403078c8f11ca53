// Building the per-frame parameters (TsFrame, kernels/shared/frame.h) from the scene.
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

#include "kernels/shared/frame.h"
#include "kernels/shared/medium.h"
#include "scene/scene.h"

namespace tessera {

/// The frame for `camera` at width × height pixels. The camera basis follows TsFrame:
/// forward = unit(look_at − position); right = unit(forward × up) · tan(vfov/2) ·
/// width/height; up' = unit(right × forward) · tan(vfov/2). Throws InputError naming
/// camera.up if up is parallel to the view direction or camera.look_at if it equals
/// the position.
TsFrame make_frame(const Camera& camera, int width, int height, uint32_t shadow_samples,
                   uint32_t seed, uint32_t light_count);

/// The far roulette's region (ts_far_importance, kernels/shared/medium.h) around the box
/// [lo, hi] (scene units): that box, grown by its diagonal, so that a path goes on as
/// before while it is within one scene size of it. Without a finite, non-empty box (no
/// triangles), margin 0: no far roulette.
ts::TsFarRegion far_region_of(glm::vec3 lo, glm::vec3 hi);

/// Sets frame.far_* (pt's far roulette) to `region`.
void set_far_region(TsFrame& frame, const ts::TsFarRegion& region);

}  // namespace tessera
