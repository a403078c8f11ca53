// The OpenCL backend: the BVH comes from Embree's builder (host/bvh), traversal and
// shading run in kernels/*.cl on any OpenCL 1.2 device. Programs are built on first
// use, so only the kernels a run needs are compiled, with the scene's defines. Every
// kernel of the kernel table takes TS_KERNEL_ARGS (kernels/tracer.h), bound by run().
// On CPU devices the igi surface and AIS item kernels and trace_occluded run as 16-ray
// packets (kernels/igi_packets.h, kernels/bvh_packet.h; docs/ray-batches.md §4): PoCL
// cannot vectorise the per-ray traversal across work-items, the packet kernels vectorise
// across 16 rays explicitly. GPUs keep one ray per work-item, with the short-stack
// traversal (-DTS_GPU_TRAVERSAL, kernels/bvh_short_stack.h). Launches run in tiles of
// about a time budget (opencl/launch.h); device buffers persist across frames, growing
// when an input outgrows them.
#include <chrono>
#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "backend/backend.h"
#include "backend/ray_order.h"
#include "bvh/bvh_builder.h"
#include "kernels/shared/geometry.h"
#include "opencl/cl.h"
#include "opencl/device.h"
#include "opencl/launch.h"
#include "opencl/program_cache.h"
#include "util/error.h"

namespace tessera {
namespace {

size_t round_up(size_t n, size_t m) { return (n + m - 1) / m * m; }

constexpr size_t kLanes = TS_PACKET_LANES;

// Below this many rays an incoherent batch is traced as given. On Sibenik the sort's gain
// on random rays grows with the batch (+2% at 16k rays, +14% at 65k, +35–40% at 262k, as
// its key cells fill up); on `ic-update` rays it was +12%, −6% and +7–10%
// (bench/results/ray_bench_sorted.md): about break-even at 16k. The renderer's own
// incoherent batches (VPL path bounces, VPL importance's 256 view points) are smaller
// and stay unsorted.
constexpr size_t kMinSortedRays = 16384;

// The packet variant of kernel `id` (kernels/igi_packets.h), or null where it has none,
// and its work-item count for a launch over `count` pixels or items.
RayKeyGrid scene_key_grid(const SceneBuffers& scene) {
    const SceneBounds& b = scene.bounds;
    return RayKeyGrid(&b.lo.x, &b.hi.x);
}

// Work items of a packet kernel (TS_KERNEL_TABLE): a pixel kernel's 4x4 blocks, or an
// item kernel's groups of kLanes items.
size_t packet_work_items(KernelId id, const TsFrame& frame, size_t count) {
    const bool blocks = kernel_info(id).item_words == 0;
    return blocks ? ts::ts_packet_block_count(&frame) : (count + kLanes - 1) / kLanes;
}

class OpenCLBackend final : public Backend {
public:
    OpenCLBackend(const SceneBuffers& scene, const EffectPlan& plan, const BackendOptions& o)
        : dev_(select_cl_device(o.device)),
          plan_(plan),
          packets_(o.cl_packets && o.cl_gpu_variant != true && cl_device_prefers_packets(dev_)),
          sort_incoherent_(o.cl_sort_incoherent),
          gpu_variant_(o.cl_gpu_variant.value_or(cl_device_prefers_short_stack(dev_))),
          light_path_kernel_(o.cl_light_path_kernel.value_or(gpu_variant_)),
          launch_ms_(o.cl_launch_ms >= 0.0 ? o.cl_launch_ms : dev_.type == "CPU" ? 0.0 : kDefaultGpuLaunchMs),
          tile_groups_(o.cl_tile_groups),
          importance_chunk_(o.cl_importance_chunk),
          light_path_gather_(o.cl_light_path_gather),
          fail_launch_(o.cl_fail_launch) {
        try {
            ctx_ = cl::Context(dev_.device);
            // Profiling: the tiles' device times size the tiles that follow, and give the
            // stages their times, without a host wait after each launch (opencl/launch.h).
            queue_ = cl::CommandQueue(ctx_, dev_.device, CL_QUEUE_PROFILING_ENABLE);
            upload_scene(scene);
            store_placeholder_inputs();
            no_items_ = upload("item list", std::vector<uint32_t>(1, 0u));
        } catch (const cl::Error& e) {
            throw RuntimeError("OpenCL setup on " + dev_.name + " failed: " + describe_cl_error(e) +
                               " (try --backend embree)");
        }
    }

    // Programs are kept unless the plan's defines change: they are what set_scene saves.
    void set_scene(const SceneBuffers& scene, const EffectPlan& plan) override {
        try {
            upload_scene(scene);
        } catch (const cl::Error& e) {
            throw RuntimeError("OpenCL upload of the scene to " + dev_.name + " failed: " + describe_cl_error(e));
        }
        if (plan.cl_defines() != plan_.cl_defines()) {
            kernels_.clear();
            programs_.clear();
        }
        plan_ = plan;
    }

    std::string description() const override {
        return "opencl (" + dev_.platform_name + ": " + dev_.name + "; " +
               (packets_ ? "16-ray packets" : gpu_variant_ ? "per-ray BVH4, short stack" : "per-ray BVH4") + ")";
    }

protected:
    void store_input(KernelInput in, const std::vector<float>& data) override {
        run([&] { store(in, data); });
    }
    void store_input(KernelInput in, const std::vector<uint32_t>& data) override {
        run([&] { store(in, data); });
    }

    void run_kernel(KernelId id, const TsFrame& frame, size_t count, const std::vector<uint32_t>& items,
             std::vector<float>& out) override {
        run([&] {
            if (!items.empty()) write(items_, items_bytes_, "item list", items);
            cl::Buffer& buf = output_buffer(out.size() * sizeof(float));
            launch_kernel(id, frame, count, items.empty() ? no_items_ : items_, buf, -1, [&] {
                queue_.enqueueReadBuffer(buf, CL_TRUE, 0, out.size() * sizeof(float), out.data());
                in_flight_.clear();  // the in-order queue has run everything up to the read
            });
        });
    }

    // The output stays in input `in`'s device buffer (no read-back); the input's own
    // argument slot gets a placeholder, so no buffer is both read and written by one launch.
    void run_kernel_into(KernelId id, const TsFrame& frame, size_t count, const std::vector<uint32_t>& items,
                         KernelInput in) override {
        const int i = static_cast<int>(in);
        run([&] {
            if (!items.empty()) write(items_, items_bytes_, "item list", items);
            const size_t bytes = count * static_cast<size_t>(kernel_info(id).out_floats) * sizeof(float);
            reserve(inputs_[i], input_bytes_[i], input_info(in).name, bytes);
            input_size_[i] = bytes;
            // No wait: the next launch queues behind this one, the stage's time comes from
            // the launch's events (kernel_seconds), and a failure found later is this
            // kernel's (in_flight_).
            launch_kernel(id, frame, count, items.empty() ? no_items_ : items_, inputs_[i], i, [] {});
        });
    }

    void fetch_input(KernelInput in, std::vector<float>& out) override {
        const int i = static_cast<int>(in);
        out.resize(input_size_[i] / sizeof(float));
        run([&] {
            queue_.enqueueReadBuffer(inputs_[i], CL_TRUE, 0, input_size_[i], out.data());
            in_flight_.clear();
        });
    }

    double program_build_seconds() const override { return program_seconds_; }

    double last_launch_seconds(KernelId id) override {
        std::vector<cl::Event>& events = launch_events_[static_cast<int>(id)];
        if (events.empty()) return Backend::last_launch_seconds(id);
        double seconds = 0.0;
        bool timed = true;
        run([&] {
            cl::Event::waitForEvents(events);
            for (const cl::Event& e : events) {
                const double s = event_seconds(e);
                timed = timed && s >= 0.0;
                seconds += s;
            }
        });
        // A device without timestamps: the call's wall time (for a launch into an input,
        // only its enqueue's).
        return timed ? seconds : Backend::last_launch_seconds(id);
    }

    void forget_launch(KernelId id) override { launch_events_[static_cast<int>(id)].clear(); }

public:
    bool resolves_on_device() const override { return gpu_variant_; }
    bool traces_light_paths_in_kernel() const override { return light_path_kernel_; }
    uint32_t importance_chunk() const override { return importance_chunk_; }
    bool gathers_light_paths() const override { return light_path_gather_; }

    // Closest hits go as packets whatever the order hint: since the packet traversal
    // keeps its lane masks as vectors (kernels/bvh_packet.h) it beats per-ray traversal
    // even on incoherent rays (bench/results/ray_bench.md, Sibenik, unsorted packets
    // against per ray: random rays 4.81 against 4.17 Mrays/s, one record point to 16 VPLs
    // 7.22 against 5.52), as any-hit packets did before. Large incoherent batches are
    // traced sorted (sorted_trace).
    void trace_closest_rays(const std::vector<float>& rays, std::vector<float>& hits, RayOrder order) override {
        hits.resize(rays.size() / TS_RAY_FLOATS * TS_HIT_FLOATS);
        sorted_trace(packets_ ? "trace_closest_packets" : "trace_closest", rays, hits.data(), TS_HIT_FLOATS, order);
    }

    void trace_occluded_rays(const std::vector<float>& rays, std::vector<uint32_t>& occluded,
                             RayOrder order) override {
        occluded.resize(rays.size() / TS_RAY_FLOATS);
        sorted_trace(packets_ ? "trace_occluded_packets" : "trace_occluded", rays, occluded.data(), 1, order);
    }

private:
    // Binds TS_KERNEL_ARGS for kernel `id` (its packet variant on packet devices), with
    // `out` as output and a placeholder for input `skip` (-1: none), then dispatches it
    // and runs `read_back`.
    template <class R>
    void launch_kernel(KernelId id, const TsFrame& frame, size_t count, cl::Buffer& items, cl::Buffer& out,
                       int skip, R&& read_back) {
        const KernelInfo& info = kernel_info(id);
        const char* packet = packets_ ? info.packet_name : nullptr;
        const size_t work_items = packet ? packet_work_items(id, frame, count) : count;
        const std::string name = packet ? packet : info.name;
        cl::Kernel& k = kernel(info.program, name);
        int a = 0;
        k.setArg(a++, sizeof(TsFrame), &frame);
        k.setArg(a++, nodes_);
        k.setArg(a++, tris_);
        for (cl::Buffer& b : scene_) k.setArg(a++, b);
        for (int i = 0; i < kKernelInputCount; ++i) k.setArg(a++, i == skip ? no_items_ : inputs_[i]);
        k.setArg(a++, items);
        k.setArg(a++, out);
        k.setArg(a++, static_cast<cl_uint>(count));
        std::vector<cl::Event>& events = launch_events_[static_cast<int>(id)];
        events.clear();
        dispatch(name, k, work_items, read_back, &events);
    }

    // An empty input is stored as one zero element: OpenCL has no empty buffers, and a
    // kernel reads an input only where the launch set it.
    template <class T>
    void store(KernelInput in, const std::vector<T>& data) {
        const int i = static_cast<int>(in);
        static const std::vector<T> one(1, T(0));
        const std::vector<T>& v = data.empty() ? one : data;
        write(inputs_[i], input_bytes_[i], input_info(in).name, v);
        input_size_[i] = v.size() * sizeof(T);
    }

    // Writes `v` into the persistent buffer `buf` of `capacity` bytes, first replacing it
    // by one 1.5× larger (at least v's size, at most one allocation) when v does not
    // fit: per-frame inputs of varying size (VPLs, item lists, rays) then allocate a few
    // times per run instead of once per frame.
    template <class T>
    void write(cl::Buffer& buf, size_t& capacity, const char* what, const std::vector<T>& v) {
        const size_t bytes = v.size() * sizeof(T);
        reserve(buf, capacity, what, bytes);
        queue_.enqueueWriteBuffer(buf, CL_TRUE, 0, bytes, v.data());
    }

    // Grows `buf` as write() does so that it holds `bytes`. Read-write: an input may also
    // be a kernel's output (run_kernel_into).
    void reserve(cl::Buffer& buf, size_t& capacity, const char* what, size_t bytes) {
        if (bytes <= capacity) return;
        check_alloc(what, bytes);
        const size_t grown = std::min<size_t>(std::max(bytes, capacity + capacity / 2), dev_.max_alloc);
        buf = cl::Buffer(ctx_, CL_MEM_READ_WRITE, grown);
        capacity = grown;
    }

    // Builds the BVH of `scene` and uploads it with the scene's buffers. The buffers are
    // replaced only once all uploads succeeded.
    void upload_scene(const SceneBuffers& scene) {
        FlatBvh bvh = build_bvh(positions_of(scene));
        cl::Buffer nodes = upload("BVH nodes", bvh.nodes), tris = upload("BVH triangles", bvh.tris);
        std::array<cl::Buffer, kSceneBufferCount> buffers = {
#define TS_UPLOAD_SCENE_BUFFER(field, type, what) upload(what, scene.field),
            TS_SCENE_BUFFERS(TS_UPLOAD_SCENE_BUFFER)
#undef TS_UPLOAD_SCENE_BUFFER
        };
        nodes_ = std::move(nodes);
        tris_ = std::move(tris);
        scene_ = std::move(buffers);
        key_grid_ = scene_key_grid(scene);
    }

    static std::vector<glm::vec3> positions_of(const SceneBuffers& s) {
        std::vector<glm::vec3> p(3 * size_t(s.triangle_count));
        if (!p.empty()) std::memcpy(p.data(), s.tri_pos.data(), p.size() * sizeof(glm::vec3));
        return p;
    }

    template <class T>
    cl::Buffer upload(const char* what, const std::vector<T>& v) {
        const size_t bytes = v.size() * sizeof(T);
        check_alloc(what, bytes);
        return cl::Buffer(ctx_, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes, const_cast<T*>(v.data()));
    }

    void check_alloc(const char* what, size_t bytes) const {
        if (bytes > dev_.max_alloc)
            throw RuntimeError(std::string("OpenCL: the ") + what + " buffer needs " + std::to_string(bytes) +
                               " bytes, more than " + dev_.name + " allows in one allocation (" +
                               std::to_string(dev_.max_alloc) + "); use --backend embree");
    }

    // Launches `k` over `work_items` in tiles of about the launch budget, then runs
    // `read_back`; a resource failure of either becomes one message naming the device,
    // the kernel and the likely causes (opencl/launch.h).
    // The launch's tile events are appended to `events` when given.
    template <class R>
    void dispatch(const std::string& name, cl::Kernel& k, size_t work_items, R&& read_back,
                  std::vector<cl::Event>* events = nullptr) {
        auto tiles = tiles_.find(name);
        if (tiles == tiles_.end()) {
            // First tile: a few work-groups per compute unit, to time the kernel.
            const size_t first = 4 * std::max(1u, dev_.compute_units);
            tiles = tiles_.emplace(name, KernelTiles{TileSizer(launch_ms_ * 1e-3, tile_groups_, first), {}}).first;
        }
        size_t tile_items = 0;
        std::vector<cl::Event> launched;
        try {
            enqueue_tiled(queue_, k, work_items, TS_WORKGROUP_SIZE, tiles->second.sizer, tiles->second.pending,
                          launched, tile_items, fail_launch_);
            for (const cl::Event& e : launched) in_flight_.emplace_back(name, e);
            if (events) events->insert(events->end(), launched.begin(), launched.end());
            read_back();
        } catch (const cl::Error& e) {
            if (!is_resource_error(e.err())) throw;
            LaunchFailure f;
            f.device = dev_.name;
            // A launch queued earlier without a wait may be the one that failed.
            const std::string failed = failed_launch(in_flight_);
            f.kernel = failed.empty() ? name : failed;
            f.error = e.err();
            f.call = e.what();
            f.tile_items = tile_items;
            f.launch_items = round_up(work_items, TS_WORKGROUP_SIZE);
            f.budget_ms = tile_groups_ > 0 ? 0.0 : launch_ms_;
            f.work_group = TS_WORKGROUP_SIZE;
            f.global_mem = dev_.global_mem;
            f.buffer_bytes = buffer_bytes();
            try {
                f.private_bytes = static_cast<size_t>(k.getWorkGroupInfo<CL_KERNEL_PRIVATE_MEM_SIZE>(dev_.device));
            } catch (const cl::Error&) {
                f.private_bytes = 0;
            }
            throw RuntimeError(launch_failure_message(f));
        }
    }

    // Bytes of every device buffer held now.
    unsigned long long buffer_bytes() const {
        unsigned long long sum = 0;
        auto add = [&](const cl::Buffer& b) {
            if (b() == nullptr) return;
            try {
                sum += b.getInfo<CL_MEM_SIZE>();
            } catch (const cl::Error&) {
            }
        };
        for (const cl::Buffer* b : {&nodes_, &tris_, &out_, &no_items_, &items_, &rays_}) add(*b);
        for (const cl::Buffer& b : scene_) add(b);
        for (const cl::Buffer& b : inputs_) add(b);
        return sum;
    }

    template <class F>
    void run(F&& f) {
        try {
            f();
        } catch (const cl::Error& e) {
            const std::string failed = is_resource_error(e.err()) ? failed_launch(in_flight_) : "";
            throw RuntimeError("OpenCL on " + dev_.name + ": " + describe_cl_error(e) +
                               (failed.empty() ? "" : " (kernel " + failed + ", queued earlier, failed)"));
        }
    }

    cl::Kernel& kernel(const std::string& program, const std::string& name) {
        auto it = kernels_.find(name);
        if (it != kernels_.end()) return it->second;
        auto p = programs_.find(program);
        if (p == programs_.end()) {
            std::vector<std::string> defines = plan_.cl_defines();
            if (gpu_variant_) defines.push_back("-DTS_GPU_TRAVERSAL");
            // Launches queued earlier finish first: their device time is pass time, and the
            // build must not be timed over it (program_build_seconds is taken out of passes).
            run([&] { queue_.finish(); });
            const auto t0 = std::chrono::steady_clock::now();
            p = programs_.emplace(program, build_program(ctx_, dev_, program, defines).program).first;
            program_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        }
        cl::Kernel k(p->second, name.c_str());
        check_kernel_limits(k, dev_, name);
        return kernels_.emplace(name, k).first->second;
    }

    cl::Buffer& output_buffer(size_t bytes) {
        if (bytes > out_bytes_) {
            check_alloc("output", bytes);
            out_ = cl::Buffer(ctx_, CL_MEM_WRITE_ONLY, bytes);
            out_bytes_ = bytes;
        }
        return out_;
    }

    // Traces `rays` with trace.cl's kernel `name` into `result` (`words` 32-bit words per
    // ray). An incoherent batch of at least kMinSortedRays rays on a packet device is
    // traced in coherent_ray_order (host/backend/ray_order.h): gathered into that order,
    // traced, and its results put back at their rays' indices. Packets of similar rays
    // traverse together, and a ray's result is the same in any order. (Reading the rays
    // through the order inside the kernel cost ~5 ms per 262k rays, the host's gather
    // ~1.5.) Measured in bench/results/ray_bench_sorted.md.
    template <class T>
    void sorted_trace(const char* name, const std::vector<float>& rays, T* result, size_t words, RayOrder order) {
        static_assert(sizeof(T) == sizeof(uint32_t), "results are 32-bit words");
        const size_t n = rays.size() / TS_RAY_FLOATS, per_item = packets_ ? kLanes : 1;
        const size_t bytes = n * words * sizeof(T);
        if (!packets_ || !sort_incoherent_ || order != RayOrder::Incoherent || n < kMinSortedRays) {
            trace(name, rays, result, bytes, per_item);
            return;
        }
        // The ray buffer first: an oversized batch fails here, before the sort's buffers.
        run([&] { reserve(rays_, rays_bytes_, "ray", rays.size() * sizeof(float)); });
        trace_in_order(name, rays, coherent_ray_order(rays.data(), n, key_grid_, sort_buffers_), result, words,
                       per_item);
        ++sorted_batches_;
    }

    // Traces `rays` in the order `perm` (perm[j]: the ray traced j-th) with kernel `name`
    // and writes each ray's `words` result words at its own index in `result`. Gathered
    // straight into the mapped ray buffer and scattered straight from the mapped results
    // (on a CPU device a map is the buffer itself): ~1.5 ms less per 262k rays than
    // staging copies.
    template <class T>
    void trace_in_order(const char* name, const std::vector<float>& rays, const std::vector<uint32_t>& perm,
                        T* result, size_t words, size_t per_item) {
        const size_t n = perm.size(), bytes = n * words * sizeof(T);
        auto in_parallel = [n](auto&& f) {
            tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t>& r) {
                for (size_t j = r.begin(); j < r.end(); ++j) f(j);
            });
        };
        const size_t ray_bytes = n * TS_RAY_FLOATS * sizeof(float);
        run([&] {
            reserve(rays_, rays_bytes_, "ray", ray_bytes);
            auto* dst = static_cast<float*>(
                queue_.enqueueMapBuffer(rays_, CL_TRUE, CL_MAP_WRITE_INVALIDATE_REGION, 0, ray_bytes));
            in_parallel([&](size_t j) {
                std::memcpy(dst + j * TS_RAY_FLOATS, &rays[perm[j] * size_t(TS_RAY_FLOATS)], TS_RAY_FLOATS * sizeof(float));
            });
            queue_.enqueueUnmapMemObject(rays_, dst);
            cl::Buffer& out = output_buffer(bytes);
            cl::Kernel& k = trace_kernel(name, n, out);
            dispatch(name, k, (n + per_item - 1) / per_item, [&] {
                const auto* src = static_cast<const T*>(queue_.enqueueMapBuffer(out, CL_TRUE, CL_MAP_READ, 0, bytes));
                in_parallel([&](size_t j) { std::memcpy(result + perm[j] * words, src + j * words, words * sizeof(T)); });
                queue_.enqueueUnmapMemObject(out, const_cast<T*>(src));
                in_flight_.clear();
            });
        });
    }

    // trace.cl's kernel `name` with its arguments bound: the BVH, the ray buffer, `n`
    // rays and the output buffer `out`.
    cl::Kernel& trace_kernel(const char* name, size_t n, cl::Buffer& out) {
        cl::Kernel& k = kernel("trace.cl", name);
        k.setArg(0, nodes_);
        k.setArg(1, tris_);
        k.setArg(2, rays_);
        k.setArg(3, static_cast<cl_uint>(n));
        k.setArg(4, out);
        return k;
    }

    // Traces `rays` with trace.cl's kernel `name`, `per_item` rays per work-item, into the
    // `result_bytes` at `result`, in the batch's own order.
    void trace(const char* name, const std::vector<float>& rays, void* result, size_t result_bytes,
               size_t per_item) {
        const size_t n = rays.size() / TS_RAY_FLOATS;
        if (n == 0) return;
        run([&] {
            write(rays_, rays_bytes_, "ray", rays);
            cl::Buffer& out = output_buffer(result_bytes);
            cl::Kernel& k = trace_kernel(name, n, out);
            dispatch(name, k, (n + per_item - 1) / per_item,
                     [&] {
                         queue_.enqueueReadBuffer(out, CL_TRUE, 0, result_bytes, result);
                         in_flight_.clear();
                     });
        });
    }

    ClDeviceInfo dev_;
    EffectPlan plan_;
    bool packets_;  // CPU device and packets wanted: the packet kernels replace their per-ray ones
    bool sort_incoherent_;  // BackendOptions::cl_sort_incoherent
    RayKeyGrid key_grid_;   // sorted_trace's origin grid: the scene's bounding box (upload_scene)
    RaySortBuffers sort_buffers_;  // sorted_trace's, kept between batches
    bool gpu_variant_;     // per-ray kernels built with -DTS_GPU_TRAVERSAL (GPU devices, or forced)
    bool light_path_kernel_;  // BackendOptions::cl_light_path_kernel
    double launch_ms_;     // launch budget, ms (0: whole launches)
    uint32_t tile_groups_; // fixed tile size in work-groups (tests; 0: by budget)
    uint32_t importance_chunk_;  // BackendOptions::cl_importance_chunk
    bool light_path_gather_;     // BackendOptions::cl_light_path_gather
    int fail_launch_ = 0;  // TESSERA_CL_FAIL_LAUNCH test hook: error code to inject
    cl::Context ctx_;
    cl::CommandQueue queue_;
    cl::Buffer nodes_, tris_, out_;
    std::array<cl::Buffer, kSceneBufferCount> scene_;  // TS_SCENE_BUFFERS order (TS_KERNEL_ARGS)
    std::array<cl::Buffer, kKernelInputCount> inputs_;  // KernelInput order (TS_KERNEL_ARGS)
    std::array<size_t, kKernelInputCount> input_bytes_{};  // their capacities
    std::array<size_t, kKernelInputCount> input_size_{};   // the bytes last written or kept
    cl::Buffer no_items_;                               // bound for pixel kernels
    cl::Buffer items_, rays_;                           // item lists, ray batches (persistent)
    size_t out_bytes_ = 0, items_bytes_ = 0, rays_bytes_ = 0;
    struct KernelTiles {
        TileSizer sizer;
        PendingTiles pending;  // tiles whose times the sizer has not seen yet
    };
    std::map<std::string, KernelTiles> tiles_;          // per kernel name
    // Each kernel's last launch (KernelId order): its tiles' events, for kernel_seconds.
    std::array<std::vector<cl::Event>, kKernelCount> launch_events_;
    // Launches since the queue was last waited for, oldest first: which kernel failed.
    InFlightLaunches in_flight_;
    std::map<std::string, cl::Program> programs_;
    double program_seconds_ = 0.0;  // building or loading programs_, for program_build_seconds()
    std::map<std::string, cl::Kernel> kernels_;
};

}  // namespace

std::unique_ptr<Backend> make_opencl_backend(const SceneBuffers& scene, const EffectPlan& plan,
                                             const BackendOptions& options) {
    return std::make_unique<OpenCLBackend>(scene, plan, options);
}

}  // namespace tessera
