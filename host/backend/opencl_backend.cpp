// The OpenCL backend: the BVH comes from Embree's builder (host/bvh), traversal and
// shading run in kernels/*.cl on any OpenCL 1.2 device. Programs are built on first
// use, so only the kernels a run needs are compiled, with the scene's defines.
#include <cstring>
#include <map>
#include <memory>
#include <string>

#include "backend/backend.h"
#include "bvh/bvh_builder.h"
#include "opencl/cl.h"
#include "opencl/device.h"
#include "opencl/program_cache.h"
#include "util/error.h"

namespace tessera {
namespace {

size_t round_up(size_t n, size_t m) { return (n + m - 1) / m * m; }

class OpenCLBackend final : public Backend {
public:
    OpenCLBackend(const SceneBuffers& scene, const EffectPlan& plan, const std::string& device)
        : dev_(select_cl_device(device)), plan_(plan) {
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
            vpls_ = upload("VPL", std::vector<float>(TS_VPL_FLOATS, 0.0f));
            vpl_set_start_ = upload("VPL set table", std::vector<uint32_t>(2, 0u));
        } catch (const cl::Error& e) {
            throw RuntimeError("OpenCL setup on " + dev_.name + " failed: " + describe_cl_error(e) +
                               " (try --backend embree)");
        }
    }

    std::string description() const override {
        return "opencl (" + dev_.platform_name + ": " + dev_.name + ")";
    }

    void set_vpls(const std::vector<float>& vpls, const std::vector<uint32_t>& set_start) override {
        run([&] {
            vpls_ = upload("VPL", vpls);
            vpl_set_start_ = upload("VPL set table", set_start);
        });
    }

protected:
    void run_pixels(PixelKernel kind, const TsFrame& frame, std::vector<float>& out) override {
        const size_t pixels = size_t(frame.width) * frame.height;
        out.resize(pixels * static_cast<size_t>(pixel_kernel_floats(kind)));
        run([&] {
            cl::Buffer& buf = output_buffer(out.size() * sizeof(float));
            cl::Kernel& k = kernel(program_of(kind), pixel_kernel_name(kind));
            set_scene_args(k, frame, buf);
            queue_.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(round_up(pixels, TS_WORKGROUP_SIZE)),
                                        cl::NDRange(TS_WORKGROUP_SIZE));
            queue_.enqueueReadBuffer(buf, CL_TRUE, 0, out.size() * sizeof(float), out.data());
        });
    }

    void run_items(const TsFrame& frame, const std::vector<uint32_t>& pixels, const std::vector<uint32_t>& codes,
                   std::vector<float>& out) override {
        run([&] {
            cl::Buffer ip = upload("AIS item pixels", pixels), ic = upload("AIS item codes", codes);
            cl::Buffer& buf = output_buffer(out.size() * sizeof(float));
            cl::Kernel& k = kernel("igi.cl", "ais_extra_pass");
            int a = set_scene_args(k, frame, buf);
            k.setArg(a++, ip);
            k.setArg(a++, ic);
            k.setArg(a++, static_cast<cl_uint>(pixels.size()));
            queue_.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(round_up(pixels.size(), TS_WORKGROUP_SIZE)),
                                        cl::NDRange(TS_WORKGROUP_SIZE));
            queue_.enqueueReadBuffer(buf, CL_TRUE, 0, out.size() * sizeof(float), out.data());
        });
    }

    void run_ic_interpolate(const std::vector<float>& gbuffer, const IcCacheBuffers& cache, float error_bound,
                            std::vector<float>& out) override {
        const size_t pixels = gbuffer.size() / TS_IC_GBUF_FLOATS;
        run([&] {
            cl::Buffer g = upload("ic G-buffer", gbuffer), n = upload("ic octree", cache.nodes);
            cl::Buffer r = upload("ic record lists", cache.refs), rec = upload("ic records", cache.records);
            cl::Buffer& buf = output_buffer(out.size() * sizeof(float));
            cl::Kernel& k = kernel("ic.cl", "ic_interpolate");
            int a = 0;
            k.setArg(a++, static_cast<cl_uint>(pixels));
            k.setArg(a++, error_bound);
            for (cl::Buffer* b : {&g, &n, &r, &rec, &buf}) k.setArg(a++, *b);
            queue_.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(round_up(pixels, TS_WORKGROUP_SIZE)),
                                        cl::NDRange(TS_WORKGROUP_SIZE));
            queue_.enqueueReadBuffer(buf, CL_TRUE, 0, out.size() * sizeof(float), out.data());
        });
    }

    // The arguments every per-pixel kernel starts with (TS_PIXEL_KERNEL_ARGS); returns
    // the index of the next argument.
    int set_scene_args(cl::Kernel& k, const TsFrame& frame, cl::Buffer& out) {
        int a = 0;
        k.setArg(a++, sizeof(TsFrame), &frame);
        for (cl::Buffer* b : {&nodes_, &tris_, &tri_pos_, &tri_nrm_, &tri_uv_, &tri_mat_, &materials_, &tex_info_,
                              &tex_texels_, &lights_, &light_cdf_, &medium_, &vpls_, &vpl_set_start_})
            k.setArg(a++, *b);
        k.setArg(a++, out);
        return a;
    }

public:
    void trace_closest(const std::vector<float>& rays, std::vector<float>& hits) override {
        hits.resize(rays.size() / TS_RAY_FLOATS * TS_HIT_FLOATS);
        trace("trace_closest", rays, hits.data(), hits.size() * sizeof(float));
    }

    void trace_occluded(const std::vector<float>& rays, std::vector<uint32_t>& occluded) override {
        occluded.resize(rays.size() / TS_RAY_FLOATS);
        trace("trace_occluded", rays, occluded.data(), occluded.size() * sizeof(uint32_t));
    }

private:
    static const char* program_of(PixelKernel k) {
        switch (k) {
            case PixelKernel::Direct: return "direct.cl";
            case PixelKernel::PathTrace: return "pt.cl";
            case PixelKernel::IcGbuffer: return "ic.cl";
            default: return "igi.cl";
        }
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
        return kernels_.emplace(name, cl::Kernel(p->second, name.c_str())).first->second;
    }

    cl::Buffer& output_buffer(size_t bytes) {
        if (bytes > out_bytes_) {
            check_alloc("output", bytes);
            out_ = cl::Buffer(ctx_, CL_MEM_WRITE_ONLY, bytes);
            out_bytes_ = bytes;
        }
        return out_;
    }

    void trace(const char* name, const std::vector<float>& rays, void* result, size_t result_bytes) {
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
            queue_.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(round_up(n, TS_WORKGROUP_SIZE)),
                                        cl::NDRange(TS_WORKGROUP_SIZE));
            queue_.enqueueReadBuffer(out, CL_TRUE, 0, result_bytes, result);
        });
    }

    ClDeviceInfo dev_;
    EffectPlan plan_;
    cl::Context ctx_;
    cl::CommandQueue queue_;
    cl::Buffer nodes_, tris_, tri_pos_, tri_nrm_, tri_uv_, tri_mat_, materials_, tex_info_, tex_texels_,
        lights_, light_cdf_, medium_, vpls_, vpl_set_start_, out_;
    size_t out_bytes_ = 0;
    std::map<std::string, cl::Program> programs_;
    std::map<std::string, cl::Kernel> kernels_;
};

}  // namespace

std::unique_ptr<Backend> make_opencl_backend(const SceneBuffers& scene, const EffectPlan& plan,
                                             const std::string& device) {
    return std::make_unique<OpenCLBackend>(scene, plan, device);
}

}  // namespace tessera
