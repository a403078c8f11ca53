// The OpenCL backend: the BVH comes from Embree's builder (host/bvh), traversal and
// shading run in kernels/*.cl on any OpenCL 1.2 device. Programs are built on first
// use, so only the kernels a run needs are compiled, with the scene's defines. Every
// kernel of the kernel table takes TS_KERNEL_ARGS (kernels/tracer.h), bound by run().
// On CPU devices the igi surface and AIS item kernels and trace_occluded run as 16-ray
// packets (kernels/igi_packets.h, kernels/bvh_packet.h; docs/ray-batches.md §4): PoCL
// cannot vectorise the per-ray traversal across work-items, the packet kernels vectorise
// across 16 rays explicitly. GPUs keep one ray per work-item.
#include <array>
#include <cstring>
#include <map>
#include <memory>
#include <string>

#include "backend/backend.h"
#include "bvh/bvh_builder.h"
#include "kernels/shared/geometry.h"
#include "opencl/cl.h"
#include "opencl/device.h"
#include "opencl/program_cache.h"
#include "util/error.h"

namespace tessera {
namespace {

size_t round_up(size_t n, size_t m) { return (n + m - 1) / m * m; }

constexpr size_t kLanes = TS_PACKET_LANES;

// The packet variant of kernel `id` (kernels/igi_packets.h), or null where it has none,
// and its work-item count for a launch over `count` pixels or items.
const char* packet_kernel(KernelId id) {
    if (id == KernelId::IgiSurface) return "igi_surface_packets";
    if (id == KernelId::AisItem) return "ais_extra_packets";
    return nullptr;
}

size_t packet_work_items(KernelId id, const TsFrame& frame, size_t count) {
    return id == KernelId::IgiSurface ? ts::ts_packet_block_count(&frame) : (count + kLanes - 1) / kLanes;
}

class OpenCLBackend final : public Backend {
public:
    OpenCLBackend(const SceneBuffers& scene, const EffectPlan& plan, const std::string& device, bool packets)
        : dev_(select_cl_device(device)), plan_(plan), packets_(packets && cl_device_prefers_packets(dev_)) {
        try {
            ctx_ = cl::Context(dev_.device);
            queue_ = cl::CommandQueue(ctx_, dev_.device);
            FlatBvh bvh = build_bvh(positions_of(scene));
            nodes_ = upload("BVH nodes", bvh.nodes);
            tris_ = upload("BVH triangles", bvh.tris);
            tri_pos_ = upload("triangle positions", scene.tri_pos);
            tri_nrm_ = upload("triangle normals", scene.tri_nrm);
            tri_uv_ = upload("triangle uvs", scene.tri_uv);
            tri_mat_ = upload("triangle materials", scene.tri_mat);
            materials_ = upload("materials", scene.materials);
            tex_info_ = upload("texture table", scene.tex_info);
            tex_texels_ = upload("textures", scene.tex_texels);
            lights_ = upload("lights", scene.lights);
            light_cdf_ = upload("light CDF", scene.light_cdf);
            medium_ = upload("medium", scene.medium);
            store(KernelInput::Vpls, std::vector<float>(TS_VPL_FLOATS, 0.0f));
            store(KernelInput::VplSetStart, std::vector<uint32_t>(2, 0u));
            for (KernelInput in : {KernelInput::IcGbuffer, KernelInput::IcNodes, KernelInput::IcRecords,
                                   KernelInput::IcRecordSurfaces})
                store(in, std::vector<float>());
            for (KernelInput in : {KernelInput::IcRefs, KernelInput::IcVisibility}) store(in, std::vector<uint32_t>());
            no_items_ = upload("item list", std::vector<uint32_t>(1, 0u));
        } catch (const cl::Error& e) {
            throw RuntimeError("OpenCL setup on " + dev_.name + " failed: " + describe_cl_error(e) +
                               " (try --backend embree)");
        }
    }

    std::string description() const override {
        return "opencl (" + dev_.platform_name + ": " + dev_.name + "; " +
               (packets_ ? "16-ray packets" : "per-ray BVH4") + ")";
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
        const KernelInfo& info = kernel_info(id);
        run([&] {
            cl::Buffer item_buf = items.empty() ? no_items_ : upload("item list", items);
            cl::Buffer& buf = output_buffer(out.size() * sizeof(float));
            const char* packet = packets_ ? packet_kernel(id) : nullptr;
            const size_t work_items = packet ? packet_work_items(id, frame, count) : count;
            cl::Kernel& k = kernel(info.program, packet ? packet : info.name);
            int a = 0;
            k.setArg(a++, sizeof(TsFrame), &frame);
            for (cl::Buffer* b : {&nodes_, &tris_, &tri_pos_, &tri_nrm_, &tri_uv_, &tri_mat_, &materials_, &tex_info_,
                                  &tex_texels_, &lights_, &light_cdf_, &medium_})
                k.setArg(a++, *b);
            for (cl::Buffer& b : inputs_) k.setArg(a++, b);
            k.setArg(a++, item_buf);
            k.setArg(a++, buf);
            k.setArg(a++, static_cast<cl_uint>(count));
            queue_.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(round_up(work_items, TS_WORKGROUP_SIZE)),
                                        cl::NDRange(TS_WORKGROUP_SIZE));
            queue_.enqueueReadBuffer(buf, CL_TRUE, 0, out.size() * sizeof(float), out.data());
        });
    }

public:
    void trace_closest_rays(const std::vector<float>& rays, std::vector<float>& hits, RayOrder) override {
        hits.resize(rays.size() / TS_RAY_FLOATS * TS_HIT_FLOATS);
        trace("trace_closest", rays, hits.data(), hits.size() * sizeof(float), 1);
    }

    void trace_occluded_rays(const std::vector<float>& rays, std::vector<uint32_t>& occluded, RayOrder) override {
        occluded.resize(rays.size() / TS_RAY_FLOATS);
        trace(packets_ ? "trace_occluded_packets" : "trace_occluded", rays, occluded.data(),
              occluded.size() * sizeof(uint32_t), packets_ ? kLanes : 1);
    }

private:
    // An empty input is stored as one zero element: OpenCL has no empty buffers, and a
    // kernel reads an input only where the launch set it.
    template <class T>
    void store(KernelInput in, const std::vector<T>& data) {
        inputs_[static_cast<int>(in)] = upload(input_info(in).name, data.empty() ? std::vector<T>(1, T(0)) : data);
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

    template <class F>
    void run(F&& f) {
        try {
            f();
        } catch (const cl::Error& e) {
            throw RuntimeError("OpenCL on " + dev_.name + ": " + describe_cl_error(e));
        }
    }

    cl::Kernel& kernel(const std::string& program, const std::string& name) {
        auto it = kernels_.find(name);
        if (it != kernels_.end()) return it->second;
        auto p = programs_.find(program);
        if (p == programs_.end())
            p = programs_.emplace(program, build_program(ctx_, dev_, program, plan_.cl_defines()).program).first;
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

    // Traces `rays` with kernel `name` of trace.cl, `per_item` rays per work-item.
    void trace(const char* name, const std::vector<float>& rays, void* result, size_t result_bytes,
               size_t per_item) {
        const size_t n = rays.size() / TS_RAY_FLOATS;
        if (n == 0) return;
        run([&] {
            check_alloc("ray", rays.size() * sizeof(float));
            cl::Buffer in(ctx_, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, rays.size() * sizeof(float),
                          const_cast<float*>(rays.data()));
            cl::Buffer& out = output_buffer(result_bytes);
            cl::Kernel& k = kernel("trace.cl", name);
            k.setArg(0, nodes_);
            k.setArg(1, tris_);
            k.setArg(2, in);
            k.setArg(3, static_cast<cl_uint>(n));
            k.setArg(4, out);
            queue_.enqueueNDRangeKernel(k, cl::NullRange,
                                        cl::NDRange(round_up((n + per_item - 1) / per_item, TS_WORKGROUP_SIZE)),
                                        cl::NDRange(TS_WORKGROUP_SIZE));
            queue_.enqueueReadBuffer(out, CL_TRUE, 0, result_bytes, result);
        });
    }

    ClDeviceInfo dev_;
    EffectPlan plan_;
    bool packets_;  // CPU device and packets wanted: the packet kernels replace their per-ray ones
    cl::Context ctx_;
    cl::CommandQueue queue_;
    cl::Buffer nodes_, tris_, tri_pos_, tri_nrm_, tri_uv_, tri_mat_, materials_, tex_info_, tex_texels_,
        lights_, light_cdf_, medium_, out_;
    std::array<cl::Buffer, kKernelInputCount> inputs_;  // KernelInput order (TS_KERNEL_ARGS)
    cl::Buffer no_items_;                               // bound for pixel kernels
    size_t out_bytes_ = 0;
    std::map<std::string, cl::Program> programs_;
    std::map<std::string, cl::Kernel> kernels_;
};

}  // namespace

std::unique_ptr<Backend> make_opencl_backend(const SceneBuffers& scene, const EffectPlan& plan,
                                             const std::string& device, bool packets) {
    return std::make_unique<OpenCLBackend>(scene, plan, device, packets);
}

}  // namespace tessera
