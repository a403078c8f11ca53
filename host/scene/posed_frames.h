// An animation's frames posed one after another (render --frames, the viewer's frames):
// what scene_at_frame finds from the rest scene alone, the objects' motion bounds and
// frame 0's VPL clamp length (a copy of every vertex and its trimmed extent; ~3.3 ms a
// Sibenik frame, bench/results/frame_setup.md), is found once for the sequence.
#pragma once
#include "scene/scene.h"

namespace tessera {

/// scene_at_frame for frames of one rest scene. `rest` is held by reference: it must
/// outlive the object and stay unchanged while it is used.
class PosedFrames {
public:
    explicit PosedFrames(const Scene& rest);
    /// Equals scene_at_frame(rest, frame), field for field; throws as it does (InputError
    /// for a frame outside the animation).
    Scene at(int frame) const;

private:
    const Scene& rest_;
    SceneBounds motion_;
    float clamp_length_;
};

}  // namespace tessera
