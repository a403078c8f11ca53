// The Embree CPU backend: rays traced with rtcIntersect1 / rtcOccluded1, pixels
// dispatched over TBB. Shading is kernels/shared compiled as C++.
#include <cstring>
#include <memory>
#include <string>

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/blocked_range2d.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include "backend/backend.h"
#include "bvh/embree_device.h"
#include "bvh/embree_scene.h"
#include "render/scene_view.h"
#include "kernels/shared/geometry.h"
#include "util/error.h"

// The tracer the shared shading code calls on this backend.
namespace tessera::ts {

struct TsTracer {
    RTCScene scene;
};

inline TsHit ts_trace_closest(const TsTracer* tr, TsRay ray) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    rh.ray.org_x = ray.org.x;
    rh.ray.org_y = ray.org.y;
    rh.ray.org_z = ray.org.z;
    rh.ray.tnear = ray.tmin;
    rh.ray.dir_x = ray.dir.x;
    rh.ray.dir_y = ray.dir.y;
    rh.ray.dir_z = ray.dir.z;
    rh.ray.time = 0.0f;
    rh.ray.tfar = ray.tmax;
    rh.ray.mask = 0xffffffffu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(tr->scene, &ctx, &rh);
    TsHit h;
    h.t = rh.ray.tfar;
    h.u = rh.hit.u;
    h.v = rh.hit.v;
    h.prim = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? TS_NO_HIT : rh.hit.primID;
    if (h.prim == TS_NO_HIT) h.u = h.v = 0.0f;
    return h;
}

inline int ts_trace_occluded(const TsTracer* tr, TsRay ray) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r;
    r.org_x = ray.org.x;
    r.org_y = ray.org.y;
    r.org_z = ray.org.z;
    r.tnear = ray.tmin;
    r.dir_x = ray.dir.x;
    r.dir_y = ray.dir.y;
    r.dir_z = ray.dir.z;
    r.time = 0.0f;
    r.tfar = ray.tmax;
    r.mask = 0xffffffffu;
    r.id = 0;
    r.flags = 0;
    rtcOccluded1(tr->scene, &ctx, &r);
    return r.tfar < 0.0f ? 1 : 0;  // Embree sets tfar to -inf on occlusion
}

}  // namespace tessera::ts

// TS_HAS_TEXTURES and TS_HAS_MEDIUM are defined for all C++ code (CMakeLists.txt): a
// material without a texture never reaches the lookup, and a scene without a medium
// has medium.present = 0, so results equal the OpenCL builds without them.
#include "kernels/shared/direct.h"
#include "kernels/shared/ic.h"
#include "kernels/shared/igi.h"
#include "kernels/shared/pt.h"

namespace tessera {
namespace {

ts::TsRay ray_from(const float* r) {
    ts::TsRay ray;
    ray.org = ts::ts_f3_load(r + TS_RAY_ORG);
    ray.tmin = r[TS_RAY_TMIN];
    ray.dir = ts::ts_f3_load(r + TS_RAY_DIR);
    ray.tmax = r[TS_RAY_TMAX];
    return ray;
}

class EmbreeBackend final : public Backend {
public:
    explicit EmbreeBackend(const SceneBuffers& scene) : buffers_(scene), scene_(build_embree_scene(scene)) {
        tracer_.scene = scene_;
    }
    ~EmbreeBackend() override { rtcReleaseScene(scene_); }

    std::string description() const override {
        return "embree (Embree 3 single rays, TBB, " +
               std::to_string(tbb::info::default_concurrency()) + " threads)";
    }

    void set_vpls(const std::vector<float>& vpls, const std::vector<uint32_t>& set_start) override {
        vpls_ = vpls;
        vpl_set_start_ = set_start;
    }

protected:
    void run_pixels(PixelKernel k, const TsFrame& frame, std::vector<float>& out) override {
        switch (k) {
            case PixelKernel::Direct: return dispatch(frame, out, k, ts::ts_direct_pixel);
            case PixelKernel::PathTrace: return dispatch(frame, out, k, ts::ts_pt_pixel);
            case PixelKernel::IgiSurface: return dispatch(frame, out, k, ts::ts_igi_surface_pixel);
            case PixelKernel::IgiMedia: return dispatch(frame, out, k, ts::ts_igi_media_pixel);
            case PixelKernel::IcGbuffer: return dispatch(frame, out, k, ts::ts_ic_gbuffer_pixel);
        }
    }

    void run_ic_interpolate(const std::vector<float>& gbuffer, const IcCacheBuffers& cache, float error_bound,
                            std::vector<float>& out) override {
        const size_t pixels = gbuffer.size() / TS_IC_GBUF_FLOATS;
        tbb::parallel_for(tbb::blocked_range<size_t>(0, pixels, 256), [&](const tbb::blocked_range<size_t>& r) {
            set_ftz_daz();
            for (size_t p = r.begin(); p < r.end(); ++p)
                ts::ts_ic_interpolate_pixel(gbuffer.data(), cache.nodes.data(), cache.refs.data(),
                                            cache.records.data(), error_bound, static_cast<uint32_t>(p),
                                            &out[TS_IC_INTERP_FLOATS * p]);
        });
    }

    void run_items(const TsFrame& frame, const std::vector<uint32_t>& pixels, const std::vector<uint32_t>& codes,
                   std::vector<float>& out) override {
        ts::TsSceneView sv = scene_view(frame);
        tbb::parallel_for(tbb::blocked_range<size_t>(0, pixels.size(), 64), [&](const tbb::blocked_range<size_t>& r) {
            set_ftz_daz();
            for (size_t i = r.begin(); i < r.end(); ++i)
                ts::ts_ais_item(&sv, &tracer_, &frame, pixels[i] % frame.width, pixels[i] / frame.width,
                                codes[i] & 0xffu, codes[i] >> 8, &out[i * TS_AIS_ITEM_FLOATS]);
        });
    }

private:
    ts::TsSceneView scene_view(const TsFrame& frame) const {
        ts::TsSceneView sv = make_scene_view(buffers_);
        sv.light_count = frame.light_count;
        sv.vpls = vpls_.data();
        sv.vpl_set_start = vpl_set_start_.data();
        return sv;
    }

    // Work is split by work-item index in the same order as the OpenCL kernels
    // (ts_pixel_of_work_item: de-interleaved by sample set when igi_tile > 1).
    template <class PixelFn>
    void dispatch(const TsFrame& frame, std::vector<float>& out, PixelKernel k, PixelFn pixel) {
        const size_t floats = static_cast<size_t>(pixel_kernel_floats(k));
        const size_t pixels = size_t(frame.width) * frame.height;
        out.resize(pixels * floats);
        ts::TsSceneView sv = scene_view(frame);
        tbb::parallel_for(tbb::blocked_range<size_t>(0, pixels, 64), [&](const tbb::blocked_range<size_t>& r) {
            set_ftz_daz();
            for (size_t i = r.begin(); i < r.end(); ++i) {
                uint32_t x, y;
                ts::ts_pixel_of_work_item(&frame, static_cast<uint32_t>(i), &x, &y);
                pixel(&sv, &tracer_, &frame, x, y, &out[(size_t(y) * frame.width + x) * floats]);
            }
        });
    }

public:

    void trace_closest(const std::vector<float>& rays, std::vector<float>& hits) override {
        const size_t n = rays.size() / TS_RAY_FLOATS;
        hits.resize(TS_HIT_FLOATS * n);
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 256), [&](const tbb::blocked_range<size_t>& r) {
            set_ftz_daz();
            for (size_t i = r.begin(); i < r.end(); ++i) {
                ts::TsHit h = ts::ts_trace_closest(&tracer_, ray_from(&rays[TS_RAY_FLOATS * i]));
                float* o = &hits[TS_HIT_FLOATS * i];
                o[TS_HIT_T] = h.t;
                o[TS_HIT_U] = h.u;
                o[TS_HIT_V] = h.v;
                std::memcpy(&o[TS_HIT_PRIM], &h.prim, 4);
            }
        });
    }

    void trace_occluded(const std::vector<float>& rays, std::vector<uint32_t>& occluded) override {
        const size_t n = rays.size() / TS_RAY_FLOATS;
        occluded.resize(n);
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 256), [&](const tbb::blocked_range<size_t>& r) {
            set_ftz_daz();
            for (size_t i = r.begin(); i < r.end(); ++i)
                occluded[i] = static_cast<uint32_t>(ts::ts_trace_occluded(&tracer_, ray_from(&rays[TS_RAY_FLOATS * i])));
        });
    }

private:
    const SceneBuffers& buffers_;
    RTCScene scene_ = nullptr;
    ts::TsTracer tracer_{};
    std::vector<float> vpls_ = std::vector<float>(TS_VPL_FLOATS, 0.0f);
    std::vector<uint32_t> vpl_set_start_ = std::vector<uint32_t>(2, 0u);
};

}  // namespace

std::unique_ptr<Backend> make_embree_backend(const SceneBuffers& scene) {
    return std::make_unique<EmbreeBackend>(scene);
}

}  // namespace tessera
