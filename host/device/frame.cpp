#include "device/frame.h"

#include <cmath>
#include <string>

#include "scene/camera_view.h"
#include "util/error.h"

namespace tessera {

TsFrame make_frame(const Camera& camera, int width, int height, uint32_t shadow_samples,
                   uint32_t seed, uint32_t light_count) {
    // The loader refuses such a camera with its key; this catches one built in code.
    if (const char* problem = camera_view_problem(camera.position, camera.look_at, camera.up))
        throw InputError(std::string("camera: ") + problem);
    const glm::vec3 fw = glm::normalize(camera.look_at - camera.position);
    glm::vec3 right = glm::normalize(glm::cross(fw, camera.up));
    glm::vec3 up = glm::normalize(glm::cross(right, fw));
    const float tan_half = std::tan(0.5f * glm::radians(camera.vfov_deg));
    right *= tan_half * static_cast<float>(width) / static_cast<float>(height);
    up *= tan_half;
    TsFrame f{};
    for (int i = 0; i < 3; ++i) {
        f.cam_pos[i] = camera.position[i];
        f.cam_forward[i] = fw[i];
        f.cam_right[i] = right[i];
        f.cam_up[i] = up[i];
    }
    f.width = static_cast<unsigned>(width);
    f.height = static_cast<unsigned>(height);
    f.shadow_samples = shadow_samples;
    f.seed = seed;
    f.light_count = light_count;
    // The angle one pixel subtends at the image centre: the image plane at distance 1
    // is 2·tan(vfov/2) tall and `height` pixels high.
    f.pixel_cone = 2.0f * tan_half / static_cast<float>(height);
    return f;
}

ts::TsFarRegion far_region_of(glm::vec3 lo, glm::vec3 hi) {
    const float diagonal = glm::length(hi - lo);
    ts::TsFarRegion r;
    r.lo = ts::make_float3(lo.x, lo.y, lo.z);
    r.hi = ts::make_float3(hi.x, hi.y, hi.z);
    r.margin = lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z && std::isfinite(diagonal) ? diagonal : 0.0f;
    return r;
}

void set_far_region(TsFrame& frame, const ts::TsFarRegion& region) {
    const float lo[3] = {region.lo.x, region.lo.y, region.lo.z}, hi[3] = {region.hi.x, region.hi.y, region.hi.z};
    for (int i = 0; i < 3; ++i) {
        frame.far_lo[i] = lo[i];
        frame.far_hi[i] = hi[i];
    }
    frame.far_margin = region.margin;
}

}  // namespace tessera
