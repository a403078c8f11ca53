#include "bvh/embree_scene.h"

#include <cstring>

#include "bvh/embree_device.h"

namespace tessera {

RTCScene build_embree_scene(const SceneBuffers& scene) {
    RTCDevice dev = embree_device();
    RTCScene s = rtcNewScene(dev);
    // The context filter serves the any-hit queries that report their triangle
    // (ts_trace_any_hit); queries without one pay a null test.
    rtcSetSceneFlags(s, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
    rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_MEDIUM);
    const size_t n = scene.triangle_count;
    if (n > 0) {
        RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
        std::memcpy(v, scene.tri_pos.data(), 9 * n * sizeof(float));
        auto* idx = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
        for (size_t i = 0; i < 3 * n; ++i) idx[i] = static_cast<unsigned>(i);
        rtcCommitGeometry(g);
        rtcAttachGeometry(s, g);
        rtcReleaseGeometry(g);
    }
    rtcCommitScene(s);
    check_embree("building the Embree scene");
    return s;
}

}  // namespace tessera
