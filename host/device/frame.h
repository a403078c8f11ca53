// Building the per-frame parameters (TsFrame, kernels/shared/frame.h) from the scene.
#pragma once
#include <cstdint>

#include "kernels/shared/frame.h"
#include "scene/scene.h"

namespace tessera {

/// The frame for `camera` at width × height pixels. The camera basis follows TsFrame:
/// forward = unit(look_at − position); right = unit(forward × up) · tan(vfov/2) ·
/// width/height; up' = unit(right × forward) · tan(vfov/2). Throws InputError naming
/// camera.up if up is parallel to the view direction or camera.look_at if it equals
/// the position.
TsFrame make_frame(const Camera& camera, int width, int height, uint32_t shadow_samples,
                   uint32_t seed, uint32_t light_count);

}  // namespace tessera
