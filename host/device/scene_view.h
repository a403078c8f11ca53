// The shared shading code's view (kernels/shared/geometry.h TsSceneView) of host-side
// scene buffers, for C++ callers of that code (the Embree backend, the benchmark).
#pragma once
#include "kernels/shared/geometry.h"
#include "device/scene_buffers.h"

namespace tessera {

/// Points at `b`'s arrays; valid while `b` lives and is not modified.
inline ts::TsSceneView make_scene_view(const SceneBuffers& b) {
    return ts::TsSceneView{b.tri_pos.data(),   b.tri_nrm.data(),   b.tri_uv.data(),
                           b.tri_mat.data(),   b.materials.data(), b.tex_info.data(),
                           b.tex_texels.data(), b.lights.data(),   b.light_cdf.data(),
                           b.medium.data(),     nullptr,            nullptr,
                           nullptr,             nullptr,            nullptr,
                           nullptr,             nullptr,            nullptr,
                           nullptr,             nullptr,            nullptr,
                           b.light_count};
}

}  // namespace tessera
