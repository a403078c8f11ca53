// The Embree CPU backend: the kernel table's shared C++ functions dispatched over TBB,
// rays traced with rtcIntersect1 / rtcOccluded1, except the igi surface pass and AIS
// items, whose shadow rays go as 16-ray packets (embree_packets.h). Shading is
// kernels/shared compiled as C++.
#include <algorithm>
#include <array>
#include <cstring>
#include <memory>
#include <string>
#include <type_traits>

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

#include "backend/embree_tracer.h"
#include "backend/embree_media_packets.h"
#include "backend/embree_ic_gather.h"
#include "backend/embree_ic_pairs.h"
#include "backend/embree_packet_loop.h"
#include "backend/embree_packets.h"

// TS_HAS_TEXTURES and TS_HAS_MEDIUM are defined for all C++ code (CMakeLists.txt): a
// material without a texture never reaches the lookup, and a scene without a medium
// has medium.present = 0, so results equal the OpenCL builds without them.
#include "kernels/shared/direct.h"
#include "kernels/shared/edge_samples.h"
#include "kernels/shared/light_path_trace.h"
#include "kernels/shared/ic.h"
#include "kernels/shared/ais_item.h"
#include "kernels/shared/igi_resolve.h"
#include "kernels/shared/pass_radiance.h"
#include "kernels/shared/pt.h"
#include "kernels/shared/vpl_importance_items.h"

namespace tessera {
namespace {

// A kernel without a packet function (TS_KERNEL_TABLE's no_packets).
struct NoPackets {};
constexpr NoPackets no_packets{};

void ic_gather_packets(const ts::TsSceneView& sv, const ts::TsTracer&, const TsFrame& frame, size_t count,
                       std::vector<float>& out) {
    ic_gather_lanes(sv, frame, count, out);
}

// Runs a kernel's packet function: a pixel kernel's (Words == 0) takes no item count. True
// when it ran (a function returning bool may decline).
template <int Words>
bool run_packets(NoPackets, const ts::TsSceneView&, const ts::TsTracer&, const TsFrame&, size_t, std::vector<float>&) {
    return false;
}
template <int Words, class Fn>
bool run_packets(Fn fn, const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame, size_t count,
                 std::vector<float>& out) {
    if constexpr (Words == 0) {
        fn(sv, tracer, frame, out);
        return true;
    } else if constexpr (std::is_same_v<decltype(fn(sv, tracer, frame, count, out)), bool>) {
        return fn(sv, tracer, frame, count, out);
    } else {
        fn(sv, tracer, frame, count, out);
        return true;
    }
}

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
    EmbreeBackend(const SceneBuffers& scene, bool packets)
        : buffers_(&scene), scene_(build_embree_scene(scene)), packets_(packets) {
        tracer_.scene = scene_;
        store_placeholder_inputs();
    }
    ~EmbreeBackend() override { rtcReleaseScene(scene_); }

    // The plan is not needed: the C++ build has every effect compiled in.
    void set_scene(const SceneBuffers& scene, const EffectPlan&) override {
        RTCScene next = build_embree_scene(scene);  // throws before anything changes
        rtcReleaseScene(scene_);
        scene_ = next;
        tracer_.scene = scene_;
        buffers_ = &scene;
    }

    std::string description() const override {
        return std::string("embree (Embree 3 ") +
               (packets_ ? "16-ray packets for igi/ais/ic rays" : "single rays") + ", TBB, " +
               std::to_string(tbb::info::default_concurrency()) + " threads)";
    }

protected:
    void store_input(KernelInput in, const std::vector<float>& data) override {
        float_inputs_[static_cast<int>(in)] = data;
    }
    void store_input(KernelInput in, const std::vector<uint32_t>& data) override {
        uint_inputs_[static_cast<int>(in)] = data;
    }

    void run_kernel_into(KernelId k, const TsFrame& frame, size_t count, const std::vector<uint32_t>& items,
                         KernelInput in) override {
        std::vector<float> out(count * static_cast<size_t>(kernel_info(k).out_floats));
        run_kernel(k, frame, count, items, out);
        float_inputs_[static_cast<int>(in)] = std::move(out);
    }
    void fetch_input(KernelInput in, std::vector<float>& out) override { out = float_inputs_[static_cast<int>(in)]; }

    void run_kernel(KernelId k, const TsFrame& frame, size_t count, const std::vector<uint32_t>& items,
                    std::vector<float>& out) override {
        ts::TsSceneView sv = scene_view(frame);
        sv.items = items.data();
        // The table's packet function where there is one and it takes the launch, else the
        // per-ray shared function.
        switch (k) {
#define TS_EMBREE_DISPATCH(id, name, program, floats, words, fn, cl_packets, packets)     \
    case KernelId::id:                                                                    \
        if (packets_ && run_packets<words>(packets, sv, tracer_, frame, count, out)) return; \
        return dispatch<floats, words>(sv, frame, count, out, ts::fn);
            TS_KERNEL_TABLE(TS_EMBREE_DISPATCH)
#undef TS_EMBREE_DISPATCH
        }
    }

private:
    ts::TsSceneView scene_view(const TsFrame& frame) const {
        ts::TsSceneView sv = make_scene_view(*buffers_);
        sv.light_count = frame.light_count;
#define TS_SCENE_VIEW_INPUT(name, field, type, what) sv.field = input<TS_ELEMENT_TYPE(type)>(KernelInput::name);
        TS_KERNEL_INPUTS(TS_SCENE_VIEW_INPUT)
#undef TS_SCENE_VIEW_INPUT
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
            const FtzDazScope ftz_daz;
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

    // Batches of rays, 16 consecutive rays per packet when packets are on, in Embree's
    // coherent mode when the caller says they are ordered so.
    void trace_closest_rays(const std::vector<float>& rays, std::vector<float>& hits, RayOrder order) override {
        const size_t n = rays.size() / TS_RAY_FLOATS;
        hits.resize(TS_HIT_FLOATS * n);
        for_each_packet(n, [&](size_t first, size_t lanes) {
            std::array<ts::TsRay, 16> r{};
            std::array<ts::TsHit, 16> h{};
            std::array<int, 16> valid{};
            for (size_t i = 0; i < lanes; ++i) r[i] = ray_from(&rays[TS_RAY_FLOATS * (first + i)]), valid[i] = -1;
            if (packets_) {
                ts::ts_trace_closest16(&tracer_, r.data(), valid.data(), order == RayOrder::Coherent16, h.data());
            } else {
                for (size_t i = 0; i < lanes; ++i) h[i] = ts::ts_trace_closest(&tracer_, r[i]);
            }
            for (size_t i = 0; i < lanes; ++i) {
                float* o = &hits[TS_HIT_FLOATS * (first + i)];
                o[TS_HIT_T] = h[i].t;
                o[TS_HIT_U] = h[i].u;
                o[TS_HIT_V] = h[i].v;
                std::memcpy(&o[TS_HIT_PRIM], &h[i].prim, 4);
            }
        });
    }

    void trace_occluded_rays(const std::vector<float>& rays, std::vector<uint32_t>& occluded,
                             RayOrder order) override {
        const size_t n = rays.size() / TS_RAY_FLOATS;
        occluded.resize(n);
        for_each_packet(n, [&](size_t first, size_t lanes) {
            std::array<ts::TsRay, 16> r{};
            std::array<int, 16> valid{};
            for (size_t i = 0; i < lanes; ++i) r[i] = ray_from(&rays[TS_RAY_FLOATS * (first + i)]), valid[i] = -1;
            if (packets_) {
                const uint32_t blocked = ts::ts_trace_occluded16(&tracer_, r.data(), valid.data(), order == RayOrder::Coherent16);
                for (size_t i = 0; i < lanes; ++i) occluded[first + i] = blocked >> i & 1u;
            } else {
                for (size_t i = 0; i < lanes; ++i)
                    occluded[first + i] = static_cast<uint32_t>(ts::ts_trace_occluded(&tracer_, r[i]));
            }
        });
    }

private:
    const SceneBuffers* buffers_;  // the caller keeps it (make_backend, set_scene)
    RTCScene scene_ = nullptr;
    ts::TsTracer tracer_{};
    bool packets_;
    // Named inputs (KernelInput order), each in the array of its element type.
    std::array<std::vector<float>, kKernelInputCount> float_inputs_;
    std::array<std::vector<uint32_t>, kKernelInputCount> uint_inputs_;
};

}  // namespace

std::unique_ptr<Backend> make_embree_backend(const SceneBuffers& scene, bool packets) {
    return std::make_unique<EmbreeBackend>(scene, packets);
}

}  // namespace tessera
