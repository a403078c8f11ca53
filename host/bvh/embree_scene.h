// The Embree scene the CPU backend traces (and the benchmark's packet tracing uses).
#pragma once
#include <embree3/rtcore.h>

#include "device/scene_buffers.h"

namespace tessera {

/// One triangle geometry holding every scene triangle, so Embree's primID is the
/// scene's triangle index. Flags: ROBUST (no accuracy-reducing traversal shortcuts,
/// so edges do not leak); build quality MEDIUM. The caller releases the scene
/// (rtcReleaseScene). Throws RuntimeError on an Embree failure.
RTCScene build_embree_scene(const SceneBuffers& scene);

}  // namespace tessera
