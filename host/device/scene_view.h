// The shared shading code's view (kernels/shared/geometry.h TsSceneView) of host-side
// scene buffers, for C++ callers of that code (the Embree backend, the benchmark).
#pragma once
#include "kernels/shared/geometry.h"
#include "device/scene_buffers.h"

namespace tessera {

/// Points at `b`'s arrays (TS_SCENE_BUFFERS, kernels/shared/kernel_inputs.h); the named
/// inputs are null. Valid while `b` lives and is not modified.
inline ts::TsSceneView make_scene_view(const SceneBuffers& b) {
    ts::TsSceneView sv{};
#define TS_SCENE_VIEW_FIELD(field, type, what) sv.field = b.field.data();
    TS_SCENE_BUFFERS(TS_SCENE_VIEW_FIELD)
#undef TS_SCENE_VIEW_FIELD
    sv.light_count = b.light_count;
    return sv;
}

}  // namespace tessera
