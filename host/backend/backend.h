// The backend seam. A backend knows how to trace rays and launch the kernels of the
// kernel table; the light transport it runs is the shared source in kernels/shared,
// identical on all backends.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "device/kernel_table.h"
#include "kernels/shared/frame.h"
#include "kernels/shared/layout_rays.h"
#include "device/effect_plan.h"
#include "device/scene_buffers.h"

namespace tessera {

enum class BackendKind { OpenCL, Embree };

/// Parses "opencl" or "embree"; throws InputError naming --backend otherwise.
BackendKind parse_backend_kind(const std::string& s);

struct BackendOptions {
    BackendOptions() = default;
    /// The backend and device; every other option at its default. (Two arguments, so
    /// that a BackendKind never converts to options by itself.)
    BackendOptions(BackendKind backend, std::string device_spec)
        : kind(backend), device(std::move(device_spec)) {}
    BackendKind kind = BackendKind::OpenCL;
    std::string device;  ///< OpenCL device spec (see select_cl_device); ignored by embree
    /// Embree: trace the igi surface pass's and AIS items' shadow rays as 16-ray packets
    /// (docs/ray-batches.md); false traces one ray at a time. Same images either way.
    bool embree_packets = true;
    /// OpenCL on CPU devices: trace the igi surface pass's and AIS items' shadow rays, and
    /// trace_occluded batches, as 16-ray packets (kernels/bvh_packet.h,
    /// docs/ray-batches.md §4); false, or a GPU, traces one ray per work-item. Same
    /// images either way.
    bool cl_packets = true;
    /// OpenCL: the GPU variant (per-ray kernels built with -DTS_GPU_TRAVERSAL: the
    /// short-stack traversal of kernels/bvh_short_stack.h). Unset: the device decides
    /// (cl_device_prefers_short_stack: GPU devices). true runs it on any device (to test
    /// it on a CPU), false runs the full-stack per-ray kernels on any device (to compare
    /// the two on a GPU). Same hits and images either way. TESSERA_CL_GPU=1 / 0 sets it
    /// per run.
    std::optional<bool> cl_gpu_variant;
    /// OpenCL: trace the VPLs' light paths in KernelId::LightPaths, a path per work item
    /// (Backend::traces_light_paths_in_kernel). Unset: where the GPU variant runs. The
    /// VPLs equal the host's batched tracing up to the device libm's last-place rounding.
    /// TESSERA_CL_LIGHT_PATHS=1 / 0 sets it per run.
    std::optional<bool> cl_light_path_kernel;
    /// OpenCL packets: trace Incoherent batches of trace_closest/trace_occluded in
    /// coherent_ray_order (host/backend/ray_order.h) and return results in the caller's
    /// order. Same results either way; false measures the unsorted packets.
    bool cl_sort_incoherent = true;
    /// OpenCL: launch budget in milliseconds (host/opencl/launch.h): launches are split
    /// into tiles of about this time. Negative: the device's default (kDefaultGpuLaunchMs
    /// on GPUs and accelerators, whole launches on CPUs); 0: whole launches.
    /// TESSERA_CL_LAUNCH_MS sets it per run.
    double cl_launch_ms = -1.0;
    /// OpenCL, for tests: tiles of exactly this many work-groups (0: sized by the budget).
    /// TESSERA_CL_TILE_GROUPS sets it per run. Same images with any tiling.
    uint32_t cl_tile_groups = 0;
    /// OpenCL, where the light paths are traced in a kernel: the VPLs each work item of the
    /// view importance's E sums take (Backend::importance_chunk); 0: all, one item a view
    /// point. TESSERA_CL_IMPORTANCE_CHUNK sets it per run. The same VPLs either way
    /// (vpl_view_importance_in_kernels); 0 until a GPU has timed the chunks against it
    /// (bench/results/gpu-h200/README.md).
    uint32_t cl_importance_chunk = 0;
    /// OpenCL, where the light paths are traced in a kernel: keep the paths' output where
    /// the kernels run and read back only its headers and the records the paths left
    /// (KernelId::LightPathGather), not every slot (1.6 KB a path, mostly empty). The same
    /// VPLs either way; two more waits for about a tenth of the bytes. Off until a GPU has
    /// timed it (Backend::gathers_light_paths). TESSERA_CL_LIGHT_PATH_GATHER=1 / 0 sets it.
    bool cl_light_path_gather = false;
    /// OpenCL, for tests: the OpenCL error code (negative) to inject after the first tile
    /// of a launch (host/opencl/launch.h); 0: off. TESSERA_CL_FAIL_LAUNCH sets it per run.
    int32_t cl_fail_launch = 0;
};

/// Traces rays and launches the kernels of the kernel table (device/kernel_table.h);
/// knows no method. Per-frame buffers the kernels read (VPLs, an irradiance cache) are
/// named inputs, kept until replaced.
class Backend {
public:
    virtual ~Backend() = default;

    /// e.g. "opencl (Portable Computing Language: pthread-...)" or "embree (TBB, 2 threads)".
    virtual std::string description() const = 0;

    /// Launches pixel kernel `k` (item_words 0) for every pixel of frame.width × height.
    /// `out` is resized to width × height × kernel_info(k).out_floats (layouts in
    /// kernels/shared/layout_*.h), row-major from the top-left pixel.
    void launch(KernelId k, const TsFrame& frame, std::vector<float>& out);

    /// Launches item kernel `k` over `items` (kernel_info(k).item_words uints per item,
    /// kernels/shared/layout_*.h). `out` is resized to out_floats per item, in list order. No launch
    /// happens for an empty list.
    void launch_items(KernelId k, const TsFrame& frame, const std::vector<uint32_t>& items, std::vector<float>& out);

    /// Launches pixel kernel `k` as launch() does, but keeps its output where the kernels
    /// run, as float input `in` of the launches that follow (on OpenCL a device buffer,
    /// never read back). Throws std::logic_error for an item kernel or a uint input.
    void launch_into(KernelId k, const TsFrame& frame, KernelInput in);

    /// Launches item kernel `k` over `items` as launch_items() does, but keeps its output
    /// (out_floats per item, in list order) where the kernels run, as float input `in`.
    /// An empty list stores the input's placeholder (one zero). Throws std::logic_error for
    /// a pixel kernel or a uint input.
    void launch_items_into(KernelId k, const TsFrame& frame, const std::vector<uint32_t>& items, KernelInput in);

    /// Launches item kernel `k` over work items 0..count−1 without a list, as
    /// launch_count_into does, into `out` (resized to out_floats per item; no launch for
    /// count 0). Throws std::logic_error for a pixel kernel.
    void launch_count(KernelId k, const TsFrame& frame, size_t count, std::vector<float>& out);

    /// Launches item kernel `k` over work items 0..count−1 without a list (a kernel that
    /// reads no item list but derives its work from its index, e.g. KernelId::AisCompactItem),
    /// keeping its output (out_floats per item) where the kernels run as float input `in`.
    /// count 0 stores the placeholder. Throws std::logic_error for a pixel kernel or a
    /// uint input.
    void launch_count_into(KernelId k, const TsFrame& frame, size_t count, KernelInput in);

    /// Reads float input `in` back from where the kernels run (as set or kept by
    /// launch_into / launch_items_into), resizing `out` to its length. Throws
    /// std::logic_error for a uint input.
    void read_input(KernelInput in, std::vector<float>& out);

    /// Whether an igi frame is best resolved (filtered and composited) where the kernels
    /// run, by KernelId::IgiResolve over inputs kept by launch_into, instead of on the
    /// host: true for OpenCL's GPU variant, where reading the kernels' outputs back costs
    /// a bus transfer of 31 floats per pixel each frame; false where kernels run in host
    /// memory (Embree, OpenCL on CPUs), whose host filter is as fast.
    virtual bool resolves_on_device() const { return false; }

    /// Whether light paths are best traced by KernelId::LightPaths, a path per work item
    /// through all its segments, instead of a launch and a read-back per bounce
    /// (trace_light_paths, gi/light_paths.h): true where the device's launches cost more
    /// than its rays (OpenCL's GPU variant); false on the CPU backends, whose batched
    /// bounces are as fast and whose VPLs then stay the host's bit for bit.
    virtual bool traces_light_paths_in_kernel() const { return false; }

    /// The VPLs a work item of KernelId::VplImportancePoints sums where the importance runs
    /// in kernels (vpl_view_importance(Backend&, ...), gi/vpl_importance.h): 0, all of
    /// them, one item a view point, unless BackendOptions::cl_importance_chunk sets it.
    virtual uint32_t importance_chunk() const { return 0; }

    /// Seconds spent so far building or loading compiled programs (OpenCL compiles a
    /// kernel's program at its first launch: a cold cache adds seconds to a render's first
    /// pass). The renderer takes it out of its pass timings, which exclude set-up. 0 where
    /// nothing is compiled (Embree).
    virtual double program_build_seconds() const { return 0.0; }

    /// Whether trace_light_paths_in_kernel reads back only the headers and records of the
    /// paths' output (BackendOptions::cl_light_path_gather; gi/light_paths.h).
    virtual bool gathers_light_paths() const { return false; }

    /// Replaces the scene the backend traces and shades, e.g. the next frame of an
    /// animation: a new BVH (built from `scene`) and new scene buffers. What does not
    /// depend on the scene is kept: the device and its context, compiled programs
    /// (rebuilt on their next use only when `plan`'s compile-time defines differ from
    /// the last plan's), persistent device buffers and the named inputs. A per-frame
    /// fresh backend spent ~3 ms loading each OpenCL program it used again
    /// (docs/ARCHITECTURE.md, "How a pass flows"). Same images as a fresh backend for
    /// `scene`, which must outlive the backend or the next set_scene; the previous scene
    /// may be freed once this returns. Throws what make_backend throws for `scene`.
    virtual void set_scene(const SceneBuffers& scene, const EffectPlan& plan) = 0;

    /// Seconds the last launch of kernel `k` took where it ran, 0 when the last call for
    /// `k` launched nothing (an empty list, count 0) or there was none: on OpenCL the
    /// device's own timestamps, summed over the launch's tiles (waiting for the launch if
    /// it is still running); on Embree its wall time. Launches into inputs (launch_into,
    /// launch_items_into, launch_count_into) queue without a host wait on OpenCL, so the
    /// wall time around one is not its time: stage timers ask this instead.
    double kernel_seconds(KernelId k) { return last_launch_seconds(k); }

    /// How many times kernel `k` was launched on this backend.
    uint64_t dispatch_count(KernelId k) const { return dispatches_[static_cast<int>(k)]; }

    /// How many trace_closest/trace_occluded batches this backend traced in a sorted order
    /// (OpenCL packets, host/backend/ray_order.h); 0 on every other backend.
    uint64_t sorted_batch_count() const { return sorted_batches_; }

    /// Sets named input `in` (layout in KernelInput's doc) for the launches that follow.
    /// Throws std::logic_error when the element type is not input_info(in)'s.
    void set_input(KernelInput in, const std::vector<float>& data);
    void set_input(KernelInput in, const std::vector<uint32_t>& data);

    /// Sets uint input `in` as set_input does, unless the last store to `in` was a call of
    /// this with equal `data`: a table that stays the same frame after frame (the light-path
    /// kernel's Halton digits, 0.2 MB at 48 bounces) then crosses a GPU's bus once, not
    /// every frame. Keeps a copy of `data` to compare with. Throws as set_input.
    void set_input_if_changed(KernelInput in, const std::vector<uint32_t>& data);
    /// How many set_input_if_changed calls stored their data (for tests).
    uint64_t changed_input_stores() const { return changed_input_stores_; }

    /// How a batch of rays is ordered, a hint that never changes results. Coherent16: each
    /// 16 consecutive rays start close together and head the same way (a 4×4 pixel tile's
    /// camera rays, shadow rays from one tile to one point); Embree then traverses them as
    /// a coherent packet (2–3× faster on such rays, about 2× slower on others,
    /// bench/results/README.md). Incoherent: anything else.
    enum class RayOrder { Incoherent, Coherent16 };

    /// Closest-hit queries. `rays` holds TS_RAY_FLOATS floats per ray (org.xyz, tmin, dir.xyz,
    /// tmax; layout_rays.h); `hits` is resized to TS_HIT_FLOATS words per ray: t, u, v as floats and the triangle
    /// index as uint bits (TS_NO_HIT on a miss, with t = tmax).
    void trace_closest(const std::vector<float>& rays, std::vector<float>& hits,
                       RayOrder order = RayOrder::Incoherent) {
        trace_closest_rays(rays, hits, order);
    }

    /// Any-hit queries: `occluded[i]` = 1 if anything lies on ray i in (tmin, tmax).
    void trace_occluded(const std::vector<float>& rays, std::vector<uint32_t>& occluded,
                        RayOrder order = RayOrder::Incoherent) {
        trace_occluded_rays(rays, occluded, order);
    }

protected:
    virtual void trace_closest_rays(const std::vector<float>& rays, std::vector<float>& hits, RayOrder order) = 0;
    virtual void trace_occluded_rays(const std::vector<float>& rays, std::vector<uint32_t>& occluded,
                                     RayOrder order) = 0;

    /// Runs `k` over `count` work items (pixels, or items of `items`) into `out`, already
    /// sized to count × out_floats.
    virtual void run_kernel(KernelId k, const TsFrame& frame, size_t count, const std::vector<uint32_t>& items,
                     std::vector<float>& out) = 0;
    /// Runs kernel `k` over `count` work items (pixels, or items of `items`) into float
    /// input `in`.
    virtual void run_kernel_into(KernelId k, const TsFrame& frame, size_t count, const std::vector<uint32_t>& items,
                                 KernelInput in) = 0;
    /// kernel_seconds: here the wall time of the last run_kernel / run_kernel_into call for
    /// `k` (what a backend that runs kernels before returning measures).
    virtual double last_launch_seconds(KernelId k) { return wall_seconds_[static_cast<int>(k)]; }
    /// Called when a launch call for `k` launches nothing: kernel_seconds(k) is then 0.
    virtual void forget_launch(KernelId k) { (void)k; }
    /// Copies float input `in` into `out` (resized).
    virtual void fetch_input(KernelInput in, std::vector<float>& out) = 0;
    virtual void store_input(KernelInput in, const std::vector<float>& data) = 0;
    virtual void store_input(KernelInput in, const std::vector<uint32_t>& data) = 0;
    /// Gives every input of TS_KERNEL_INPUTS a placeholder before any is set, alike on
    /// every backend: one zero element of its type (OpenCL has no empty buffers), and for
    /// the VPLs a valid empty VPL set table (one zero VPL, set starts {0, 0}). A kernel is
    /// then always bound to a real buffer (element 0 reads 0), never a null pointer or a
    /// NULL buffer; reading past element 0 of an input nobody set is the caller's error.
    /// Derived constructors call it once their storage exists.
    void store_placeholder_inputs();

    uint64_t sorted_batches_ = 0;  ///< counted by backends that sort batches (sorted_batch_count)

private:
    // Counts and times a launch of `k` that calls `run`; forgets k's last launch when
    // `count` is 0 (nothing launches).
    template <class F>
    void dispatch_timed(KernelId k, size_t count, F&& run);

    uint64_t dispatches_[kKernelCount] = {};
    double wall_seconds_[kKernelCount] = {};
    // What set_input_if_changed last stored in each input; unset once anything else has.
    std::optional<std::vector<uint32_t>> unchanged_[kKernelInputCount];
    uint64_t changed_input_stores_ = 0;
};

/// Creates a backend for `scene`. The OpenCL backend builds its BVH with Embree's
/// builder and uploads every buffer; the Embree backend builds an Embree scene.
/// `scene` must outlive the backend. Throws RuntimeError when the device cannot be
/// used (with a hint to --backend embree).
std::unique_ptr<Backend> make_backend(const BackendOptions& options, const SceneBuffers& scene,
                                      const EffectPlan& plan);

/// The backend of a sequence of scenes (animation frames): `backend` given `scene` with
/// Backend::set_scene when it exists, else made for it with make_backend(options, ...).
/// The same requirements on `scene` and the same errors as those two.
void give_scene(std::unique_ptr<Backend>& backend, const BackendOptions& options, const SceneBuffers& scene,
                const EffectPlan& plan);

std::unique_ptr<Backend> make_embree_backend(const SceneBuffers& scene, bool packets = true);
/// The OpenCL backend with `options` as given (make_backend applies the TESSERA_CL_*
/// environment overrides first).
std::unique_ptr<Backend> make_opencl_backend(const SceneBuffers& scene, const EffectPlan& plan,
                                             const BackendOptions& options);

}  // namespace tessera
