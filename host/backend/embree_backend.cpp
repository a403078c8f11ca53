// The Embree CPU backend: rays traced with rtcIntersect1 / rtcOccluded1, the kernel
// table's shared C++ functions dispatched over TBB. Shading is kernels/shared compiled
// as C++.
#include <array>
#include <cstring>
#include <type_traits>
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
#include "device/scene_view.h"
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
        store_input(KernelInput::Vpls, std::vector<float>(TS_VPL_FLOATS, 0.0f));
        store_input(KernelInput::VplSetStart, std::vector<uint32_t>(2, 0u));
    }
    ~EmbreeBackend() override { rtcReleaseScene(scene_); }

    std::string description() const override {
        return "embree (Embree 3 single rays, TBB, " +
               std::to_string(tbb::info::default_concurrency()) + " threads)";
    }

protected:
    void store_input(KernelInput in, const std::vector<float>& data) override {
        float_inputs_[static_cast<int>(in)] = data;
    }
    void store_input(KernelInput in, const std::vector<uint32_t>& data) override {
        uint_inputs_[static_cast<int>(in)] = data;
    }

    void run_kernel(KernelId k, const TsFrame& frame, size_t count, const std::vector<uint32_t>& items,
                    std::vector<float>& out) override {
        ts::TsSceneView sv = scene_view(frame);
        sv.items = items.data();
        switch (k) {
#define TS_EMBREE_DISPATCH(id, name, program, floats, words, fn) \
    case KernelId::id: return dispatch<floats, words>(sv, frame, count, out, ts::fn);
            TS_KERNEL_TABLE(TS_EMBREE_DISPATCH)
#undef TS_EMBREE_DISPATCH
        }
    }

private:
    ts::TsSceneView scene_view(const TsFrame& frame) const {
        ts::TsSceneView sv = make_scene_view(buffers_);
        sv.light_count = frame.light_count;
        sv.vpls = input<float>(KernelInput::Vpls);
        sv.vpl_set_start = input<uint32_t>(KernelInput::VplSetStart);
        sv.ic_gbuffer = input<float>(KernelInput::IcGbuffer);
        sv.ic_nodes = input<float>(KernelInput::IcNodes);
        sv.ic_refs = input<uint32_t>(KernelInput::IcRefs);
        sv.ic_records = input<float>(KernelInput::IcRecords);
        sv.ic_record_surfaces = input<float>(KernelInput::IcRecordSurfaces);
        sv.ic_visibility = input<uint32_t>(KernelInput::IcVisibility);
        return sv;
    }

    template <class T>
    const T* input(KernelInput in) const {
        if constexpr (std::is_same_v<T, float>) return float_inputs_[static_cast<int>(in)].data();
        else return uint_inputs_[static_cast<int>(in)].data();
    }

    // Pixel kernels (Words == 0): work is split by work-item index in the same order as
    // the OpenCL kernels (ts_pixel_of_work_item: de-interleaved by sample set when
    // igi_tile > 1), each pixel's output at its place. Item kernels: item i's output at
    // place i.
    template <int Floats, int Words, class Fn>
    void dispatch(const ts::TsSceneView& sv, const TsFrame& frame, size_t count, std::vector<float>& out, Fn fn) {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 64), [&](const tbb::blocked_range<size_t>& r) {
            set_ftz_daz();
            for (size_t i = r.begin(); i < r.end(); ++i) {
                if constexpr (Words == 0) {
                    uint32_t x, y;
                    ts::ts_pixel_of_work_item(&frame, static_cast<uint32_t>(i), &x, &y);
                    fn(&sv, &tracer_, &frame, x, y, &out[(size_t(y) * frame.width + x) * Floats]);
                } else {
                    fn(&sv, &tracer_, &frame, static_cast<uint32_t>(i), &out[i * Floats]);
                }
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
    // Named inputs (KernelInput order), each in the array of its element type.
    std::array<std::vector<float>, kKernelInputCount> float_inputs_;
    std::array<std::vector<uint32_t>, kKernelInputCount> uint_inputs_;
};

}  // namespace

std::unique_ptr<Backend> make_embree_backend(const SceneBuffers& scene) {
    return std::make_unique<EmbreeBackend>(scene);
}

}  // namespace tessera
