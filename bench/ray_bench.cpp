// Ray throughput by ray kind and `direct` frame time: OpenCL (default device: PoCL),
// Embree single rays and Embree 16-ray packets, in one process on the same rays. Writes
// JSON and a markdown table (bench/results/ray_bench.*).
//
// Ray kinds on the scene's camera view (default Sibenik at 512×512), pixels listed in 4×4
// tiles so that 16 consecutive rays come from one tile (the grouping the renderer's
// packets use, docs/ray-batches.md):
//   primary  camera rays through pixel centres (closest hit)
//   light    from the tile's 16 primary hits to one point on an area light per tile (any
//            hit): IGI's light-sample shadow rays, one sample shared by a set's pixels
//   vpl      from the tile's 16 hits to one VPL per tile, a random surface point seen
//            from the camera (any hit): IGI's VPL shadow rays
//   ic       the instant cache's placement pairs as the renderer lists them (closest hit:
//            the cache keeps the occluder): VPL by VPL, each from the records of a pixel
//            grid in Morton order of their cells (16 consecutive rays: a 4×4 block of
//            records to one VPL). The records are the primary hits on the stride-8 grid,
//            placement's first and only dense level (host/gi/instant_cache.cpp); its
//            finer levels place sparser records, whose packets are less coherent
//   ic-update  the temporal update's re-traced pairs, listed record by record: from one
//            record point (a tile's first hit) to 16 different VPLs
//   random   from each primary hit in a uniform random direction (closest hit; the
//            incoherent case)
// Every tracer gets the rays in the batch form the renderer issues: OpenCL one upload,
// kernel and read-back per query, per ray (TESSERA_CL_PACKETS=0 form) and as by default
// (16 consecutive rays per work-item on CPU devices, kernels/bvh_packet.h; incoherent
// batches sorted first, host/backend/ray_order.h), unsorted packets (the default before
// the sort), and the GPU variant (per ray with the short-stack traversal of
// kernels/bvh_short_stack.h, forced on the CPU device: what it costs there; its GPU
// rates need a GPU); Embree single rtcIntersect1/rtcOccluded1 per
// ray over TBB; Embree packets rtcIntersect16/rtcOccluded16 over 16 consecutive rays
// (Backend::trace_* of the Embree backend with packets on; Embree's coherent mode for
// primary, light, vpl and ic, as the renderer's packets use it, incoherent for ic-update
// and random).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include "backend/backend.h"
#include "bench/machine.h"
#include "bvh/embree_device.h"
#include "kernels/shared/geometry.h"
#include "kernels/shared/sampling.h"
#include "device/frame.h"
#include "render/renderer.h"
#include "device/scene_view.h"
#include "scene/loader.h"
#include "util/morton.h"
#include "util/heap.h"

using namespace tessera;
namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

template <class F>
double median_seconds(int repeats, F&& f) {
    std::vector<double> t;
    for (int i = 0; i < repeats; ++i) {
        auto t0 = Clock::now();
        f();
        t.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

struct RaySet {
    const char* name;
    bool closest;  // closest hit (else any hit)
    std::vector<float> rays;
    Backend::RayOrder order = Backend::RayOrder::Incoherent;
};

void push_ray(std::vector<float>& rays, ts::float3 o, ts::float3 d, float tmax) {
    rays.insert(rays.end(), {o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, tmax});
}

// Pixel i of a w × h image listed tile by tile (4×4 tiles, row-major within a tile).
void tiled_pixel(int i, int w, int* x, int* y) {
    const int tile = i / 16, tx = tile % (w / 4), ty = tile / (w / 4);
    *x = tx * 4 + (i % 16) % 4;
    *y = ty * 4 + (i % 16) / 4;
}

std::vector<RaySet> make_rays(const Scene& scene, const SceneBuffers& b, Backend& embree, int w, int h) {
    TsFrame f = make_frame(scene.camera, w, h, 1, 1, b.light_count);
    RaySet primary{"primary", true, {}}, light{"light", false, {}}, vpl{"vpl", false, {}}, ic{"ic", true, {}},
        ic_update{"ic-update", true, {}}, random{"random", true, {}};
    for (int i = 0; i < w * h; ++i) {
        int x, y;
        tiled_pixel(i, w, &x, &y);
        const ts::TsRay ray = ts::ts_camera_ray(&f, x, y, 0.5f, 0.5f);
        push_ray(primary.rays, ray.org, ray.dir, INFINITY);
    }
    std::vector<float> hits;
    embree.trace_closest(primary.rays, hits);
    const ts::TsSceneView sv = make_scene_view(b);
    struct Point {
        ts::float3 origin, position, normal;
    };
    std::vector<Point> points;  // the primary hits, tile order
    std::vector<int> point_of(size_t(w) * h, -1);  // pixel -> index in points
    for (size_t i = 0; i < primary.rays.size() / TS_RAY_FLOATS; ++i) {
        const float* hi = &hits[TS_HIT_FLOATS * i];
        uint32_t prim;
        std::memcpy(&prim, &hi[TS_HIT_PRIM], 4);
        if (prim == TS_NO_HIT) continue;
        const float* pr = &primary.rays[TS_RAY_FLOATS * i];
        const ts::TsRay r{ts::ts_f3_load(pr + TS_RAY_ORG), ts::ts_f3_load(pr + TS_RAY_DIR), 0.0f, INFINITY};
        const ts::TsHit hit{hi[TS_HIT_T], hi[TS_HIT_U], hi[TS_HIT_V], prim};
        const ts::TsSurface s = ts::ts_surface_at(&sv, r, hit);
        int x, y;
        tiled_pixel(static_cast<int>(i), w, &x, &y);
        point_of[size_t(y) * w + x] = static_cast<int>(points.size());
        points.push_back({ts::ts_offset_ray_origin(s.origin, s.geo_normal, s.pos_scale), s.position, s.geo_normal});
    }
    std::vector<std::pair<uint32_t, int>> cells;  // (Morton code, point) of the stride-8 records
    for (int y = 0; y < h; y += 8)
        for (int x = 0; x < w; x += 8)
            if (const int p = point_of[size_t(y) * w + x]; p >= 0) cells.push_back({morton2(x / 8, y / 8), p});
    std::sort(cells.begin(), cells.end());
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::normal_distribution<float> g;
    auto any_point = [&] { return points[std::min(points.size() - 1, size_t(u(rng) * points.size()))]; };
    ts::float3 to_light{}, to_vpl{};
    for (size_t i = 0; i < points.size(); ++i) {
        if (i % 16 == 0) {  // one light sample and one VPL per 16 rays
            const ts::TsLightSample ls =
                ts::ts_sample_light(b.lights.data(), b.light_cdf.data(), b.light_count, u(rng), u(rng), u(rng));
            to_light = ls.position;
            const Point v = any_point();
            to_vpl = v.position + v.normal * (1e-4f * ts::length(v.position) + 1e-4f);
        }
        const ts::float3 o = points[i].origin;
        push_ray(light.rays, o, to_light - o, 0.99999f);
        push_ray(vpl.rays, o, to_vpl - o, 0.99999f);
        const Point rec = points[i - i % 16], v = any_point();
        push_ray(ic_update.rays, rec.origin, v.position + v.normal * 1e-3f - rec.origin, 0.99999f);
        ts::float3 dr = ts::normalize(ts::make_float3(g(rng), g(rng), g(rng)));
        if (ts::dot(dr, points[i].normal) < 0.0f) dr = -dr;  // leave the surface on its lit side
        push_ray(random.rays, o, dr, INFINITY);
    }
    ts::float3 to{};
    for (size_t i = 0; i < points.size(); ++i) {  // VPL by VPL, the records in Morton order
        if (i % cells.size() == 0) {
            const Point v = any_point();
            to = v.position + v.normal * 1e-3f;
        }
        const Point rec = points[cells[i % cells.size()].second];
        push_ray(ic.rays, rec.origin, to - rec.origin, 0.99999f);
    }
    for (RaySet* s : {&primary, &light, &vpl, &ic}) s->order = Backend::RayOrder::Coherent16;
    return {primary, light, vpl, ic, ic_update, random};
}

}  // namespace

int main(int argc, char** argv) {
    tessera::keep_frame_memory();
    CLI::App app{"Tessera ray-throughput and frame-time benchmark"};
    std::string scene_path = std::string(TESSERA_SCENES_DIR) + "/sibenik.json", out_dir = "bench/results";
    std::string device;
    int repeats = 7, size = 512;
    std::vector<std::string> kinds;
    bool direct_frame = true;
    app.add_option("--scene", scene_path);
    app.add_option("--device", device, "OpenCL device");
    app.add_option("--repeats", repeats)->capture_default_str();
    app.add_option("--size", size, "image width and height")->capture_default_str();
    app.add_option("--kinds", kinds, "ray kinds to measure (default all): primary light vpl ic ic-update random")
        ->check(CLI::IsMember({"primary", "light", "vpl", "ic", "ic-update", "random"}))
        ->delimiter(',');
    app.add_flag("!--no-direct", direct_frame, "skip the `direct` frame times");
    app.add_option("--out", out_dir, "directory for ray_bench.json and ray_bench.md")->capture_default_str();
    CLI11_PARSE(app, argc, argv);

    Scene scene = load_scene(scene_path, make_data_path(std::nullopt));
    SceneBuffers b = make_scene_buffers(scene);
    EffectPlan plan = plan_effects(scene);
    BackendOptions single_opts{BackendKind::Embree, ""};
    single_opts.embree_packets = false;
    auto em = make_backend(single_opts, b, plan);
    auto pk = make_backend({BackendKind::Embree, ""}, b, plan);
    auto cl = make_backend({BackendKind::OpenCL, device}, b, plan);  // packets on CPU devices
    BackendOptions cl_ray_opts{BackendKind::OpenCL, device};
    cl_ray_opts.cl_packets = false;
    cl_ray_opts.cl_gpu_variant = false;  // the full-stack per-ray kernels, on a GPU too
    auto clr = make_backend(cl_ray_opts, b, plan);
    BackendOptions cl_unsorted_opts{BackendKind::OpenCL, device};
    cl_unsorted_opts.cl_sort_incoherent = false;
    auto clu = make_backend(cl_unsorted_opts, b, plan);
    BackendOptions cl_gpu_opts{BackendKind::OpenCL, device};
    cl_gpu_opts.cl_gpu_variant = true;
    auto clg = make_backend(cl_gpu_opts, b, plan);
    const std::vector<RaySet> sets = make_rays(scene, b, *em, size, size);

    nlohmann::json j;
    j["machine"] = {{"cpu", bench::cpu_model()}, {"threads", tbb::info::default_concurrency()},
                    {"opencl", cl->description()}, {"embree", pk->description()}};
    j["scene"] = scene.name;
    j["triangles"] = scene.triangle_count();
    j["size"] = size;
    j["repeats"] = repeats;
    std::vector<float> hits;
    std::vector<uint32_t> occ;
    cl->trace_closest(sets[0].rays, hits);  // warm-up: builds (or loads) the trace program
    cl->trace_occluded(sets[1].rays, occ);
    clr->trace_occluded(sets[1].rays, occ);
    clg->trace_occluded(sets[1].rays, occ);
    auto mrays = [](size_t n, double s) { return n / s * 1e-6; };
    struct Row {
        std::string name;
        size_t n;
        double clr, clg, clu, cl, em, pk;  // OpenCL per ray, GPU variant, unsorted, as default; Embree single, packets
    };
    std::vector<Row> rows;
    for (const RaySet& set : sets) {
        if (!kinds.empty() && std::find(kinds.begin(), kinds.end(), set.name) == kinds.end()) continue;
        auto rate = [&](Backend& be) {
            auto trace = [&] {
                if (set.closest) be.trace_closest(set.rays, hits, set.order);
                else be.trace_occluded(set.rays, occ, set.order);
            };
            // One untimed run first: on a GPU the first launches of a kernel also pay for
            // its loading and the clocks' ramp from idle (the same kernels measured 2.2x
            // apart on an H100 without it, bench/results/gpu-h100/README.md).
            trace();
            return mrays(set.rays.size() / TS_RAY_FLOATS, median_seconds(repeats, trace));
        };
        Row row{set.name, set.rays.size() / TS_RAY_FLOATS, rate(*clr), rate(*clg), rate(*clu), rate(*cl), rate(*em), rate(*pk)};
        rows.push_back(row);
        std::fprintf(stderr, "%-8s %8zu rays  OpenCL per ray %6.2f  GPU variant %6.2f  unsorted %6.2f  default %6.2f  "
                     "Embree single %6.2f  packets %6.2f Mrays/s\n",
                     set.name, row.n, row.clr, row.clg, row.clu, row.cl, row.em, row.pk);
        j["rays"][row.name] = {{"count", row.n},
                               {"closest_hit", set.closest},
                               {"opencl_per_ray_mrays_s", row.clr},
                               {"opencl_gpu_variant_mrays_s", row.clg},
                               {"opencl_unsorted_mrays_s", row.clu},
                               {"opencl_mrays_s", row.cl},
                               {"embree_single_mrays_s", row.em},
                               {"embree_packet16_mrays_s", row.pk},
                               {"packets_over_single", row.pk / row.em},
                               {"opencl_over_embree_single", row.cl / row.em},
                               {"opencl_over_embree_packets", row.cl / row.pk}};
    }

    RenderSettings rs;
    rs.width = rs.height = size;
    rs.shadow_samples = 16;
    rs.spp = static_cast<uint32_t>(repeats);
    RenderStats scl, sem;
    if (direct_frame) {
        render_frame(*cl, scene, b, rs, &scl);
        render_frame(*pk, scene, b, rs, &sem);
        j["direct_frame"] = {{"shadow_samples", 16}, {"opencl_ms", 1e3 * scl.median_pass_seconds},
                             {"embree_ms", 1e3 * sem.median_pass_seconds},
                             {"opencl_over_embree_speed", sem.median_pass_seconds / scl.median_pass_seconds}};
        std::fprintf(stderr, "direct %dx%d, 16 shadow samples: OpenCL %.1f ms, Embree %.1f ms per frame\n", size, size,
                     1e3 * scl.median_pass_seconds, 1e3 * sem.median_pass_seconds);
    }

    fs::create_directories(out_dir);
    std::ofstream(fs::path(out_dir) / "ray_bench.json") << j.dump(2) << "\n";
    std::ofstream md(fs::path(out_dir) / "ray_bench.md");
    md << "# Ray throughput and `direct` frame time: " << scene.name << ", " << size << "x" << size << "\n\n"
       << "Machine: " << j["machine"]["cpu"].get<std::string>() << ", " << tbb::info::default_concurrency()
       << " threads. OpenCL: " << cl->description() << ". Medians of " << repeats << " runs.\n\n"
       << "| rays | count | OpenCL per ray | OpenCL GPU variant | OpenCL packets unsorted | OpenCL default | Embree single | "
          "Embree packets | Embree packets / single | OpenCL default / Embree single | OpenCL default / Embree packets |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|\n";
    char buf[256];
    for (const auto& r : rows) {
        std::snprintf(buf, sizeof buf, "| %s | %zu | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |\n",
                      r.name.c_str(), r.n, r.clr, r.clg, r.clu, r.cl, r.em, r.pk, r.pk / r.em, r.cl / r.em, r.cl / r.pk);
        md << buf;
    }
    md << "\nRates in Mrays/s. OpenCL per ray: the full-stack traversal (TESSERA_CL_GPU=0 on a GPU). "
          "OpenCL default on CPU devices: 16-ray packets for every kind "
          "(trace_occluded_packets, trace_closest_packets), incoherent batches (ic-update, random) traced in "
          "coherent_ray_order, the sort's time included (host/backend/ray_order.h); OpenCL packets unsorted: the same "
          "without the sort (BackendOptions::cl_sort_incoherent = false). OpenCL GPU variant: per ray with the short-stack traversal "
          "(TESSERA_CL_GPU=1), the default on GPU devices. Ray kinds and how each tracer is driven: the header of "
          "bench/ray_bench.cpp.\n";
    if (direct_frame) {
        std::snprintf(buf, sizeof buf,
                      "\n`direct`, 16 shadow samples, 1 spp: OpenCL %.1f ms, Embree %.1f ms per frame "
                      "(Embree time / OpenCL time = %.2f).\n",
                      1e3 * scl.median_pass_seconds, 1e3 * sem.median_pass_seconds,
                      sem.median_pass_seconds / scl.median_pass_seconds);
        md << buf;
    }
    return 0;
}
