#include "scene/posed_frames.h"

#include "scene/animation.h"

namespace tessera {

PosedFrames::PosedFrames(const Scene& rest)
    : rest_(rest), motion_(motion_bounds(rest)), clamp_length_(motion_.empty() ? 0.0f : frame_zero_clamp_length(rest)) {}

Scene PosedFrames::at(int frame) const { return scene_detail::pose_frame(rest_, frame, motion_, clamp_length_); }

}  // namespace tessera
