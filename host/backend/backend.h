// The backend seam. A backend knows how to trace rays and dispatch work; the light
// transport it runs is the shared source in kernels/shared, identical on all backends.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "kernels/shared/layout.h"
#include "render/effect_plan.h"
#include "render/method.h"
#include "render/scene_buffers.h"

namespace tessera {

enum class BackendKind { OpenCL, Embree };

/// An irradiance cache as the interpolation kernel reads it (kernels/shared/ic.h):
/// TS_IC_NODE_FLOATS per octree node (root first), the nodes' record lists
/// concatenated, and TS_IC_RECORD_FLOATS per record.
struct IcCacheBuffers {
    std::vector<float> nodes;
    std::vector<uint32_t> refs;
    std::vector<float> records;
};

/// Parses "opencl" or "embree"; throws InputError naming --backend otherwise.
BackendKind parse_backend_kind(const std::string& s);

struct BackendOptions {
    BackendKind kind = BackendKind::OpenCL;
    std::string device;  ///< OpenCL device spec (see select_cl_device); ignored by embree
};

class Backend {
public:
    virtual ~Backend() = default;

    /// e.g. "opencl (Portable Computing Language: pthread-...)" or "embree (TBB, 2 threads)".
    virtual std::string description() const = 0;

    /// Runs per-pixel kernel `k` for every pixel of frame.width × height. `out` is
    /// resized to width × height × pixel_kernel_floats(k) (layouts in layout.h),
    /// row-major from the top-left pixel.
    void render_pass(PixelKernel k, const TsFrame& frame, std::vector<float>& out) {
        ++dispatches_[static_cast<int>(k)];
        run_pixels(k, frame, out);
    }

    /// Runs the AIS extra kernel (kernels/shared/igi.h ts_ais_item) over work items:
    /// item i evaluates sample set codes[i] & 0xff for the TS_COMPONENT_* bits
    /// codes[i] >> 8 at pixel pixels[i] (row-major index). `out` is resized to
    /// TS_AIS_ITEM_FLOATS per item. No dispatch happens for an empty list.
    void render_items(const TsFrame& frame, const std::vector<uint32_t>& pixels, const std::vector<uint32_t>& codes,
                      std::vector<float>& out) {
        out.resize(pixels.size() * TS_AIS_ITEM_FLOATS);
        if (pixels.empty()) return;
        ++item_dispatches_;
        run_items(frame, pixels, codes, out);
    }

    /// Instant caching: interpolates `cache` at every pixel of `gbuffer` (TS_IC_GBUF_FLOATS
    /// per pixel, from PixelKernel::IcGbuffer) with error bound `error_bound` (Ward's a).
    /// `out` is resized to TS_IC_INTERP_FLOATS floats per pixel (layout.h): E (irradiance / π)
    /// and the weight sum.
    void ic_interpolate(const std::vector<float>& gbuffer, const IcCacheBuffers& cache, float error_bound,
                        std::vector<float>& out) {
        const size_t pixels = gbuffer.size() / TS_IC_GBUF_FLOATS;
        out.assign(TS_IC_INTERP_FLOATS * pixels, 0.0f);
        if (pixels == 0) return;
        ++ic_dispatches_;
        run_ic_interpolate(gbuffer, cache, error_bound, out);
    }

    /// How many times the ic interpolation kernel was dispatched.
    uint64_t ic_dispatch_count() const { return ic_dispatches_; }

    /// How many times the AIS extra kernel was dispatched.
    uint64_t item_dispatch_count() const { return item_dispatches_; }

    /// How many times kernel `k` was dispatched on this backend.
    uint64_t dispatch_count(PixelKernel k) const { return dispatches_[static_cast<int>(k)]; }

    /// Sets the VPLs the igi kernels gather from: TS_VPL_FLOATS per VPL, sorted by
    /// sample set; set_start holds N + 1 offsets (set k is [set_start[k], set_start[k+1])).
    virtual void set_vpls(const std::vector<float>& vpls, const std::vector<uint32_t>& set_start) = 0;

    /// Closest-hit queries. `rays` holds TS_RAY_FLOATS floats per ray (org.xyz, tmin, dir.xyz,
    /// tmax; layout.h); `hits` is resized to TS_HIT_FLOATS words per ray: t, u, v as floats and the triangle
    /// index as uint bits (TS_NO_HIT on a miss, with t = tmax).
    virtual void trace_closest(const std::vector<float>& rays, std::vector<float>& hits) = 0;

    /// Any-hit queries: `occluded[i]` = 1 if anything lies on ray i in (tmin, tmax).
    virtual void trace_occluded(const std::vector<float>& rays, std::vector<uint32_t>& occluded) = 0;

protected:
    virtual void run_pixels(PixelKernel k, const TsFrame& frame, std::vector<float>& out) = 0;
    virtual void run_items(const TsFrame& frame, const std::vector<uint32_t>& pixels,
                           const std::vector<uint32_t>& codes, std::vector<float>& out) = 0;
    virtual void run_ic_interpolate(const std::vector<float>& gbuffer, const IcCacheBuffers& cache,
                                    float error_bound, std::vector<float>& out) = 0;

private:
    uint64_t dispatches_[kPixelKernelCount] = {};
    uint64_t item_dispatches_ = 0;
    uint64_t ic_dispatches_ = 0;
};

/// Creates a backend for `scene`. The OpenCL backend builds its BVH with Embree's
/// builder and uploads every buffer; the Embree backend builds an Embree scene.
/// `scene` must outlive the backend. Throws RuntimeError when the device cannot be
/// used (with a hint to --backend embree).
std::unique_ptr<Backend> make_backend(const BackendOptions& options, const SceneBuffers& scene,
                                      const EffectPlan& plan);

std::unique_ptr<Backend> make_embree_backend(const SceneBuffers& scene);
std::unique_ptr<Backend> make_opencl_backend(const SceneBuffers& scene, const EffectPlan& plan,
                                             const std::string& device);

}  // namespace tessera
