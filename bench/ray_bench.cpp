// Ray throughput and `direct` frame time, OpenCL (default device: PoCL) against Embree,
// in one process on the same rays. Writes JSON and a markdown table.
//
// Ray sets on the scene's camera view (default Sibenik at 512×512):
//   primary  camera rays through pixel centres (closest hit)
//   shadow   from each primary hit to a power-sampled point on an area light (any hit)
//   random   from each primary hit in a uniform random direction over the sphere
//            (closest hit; the incoherent case)
// OpenCL times include the ray upload and result read-back (one batch per query, as the
// renderer would issue them); Embree single rays run rtcIntersect1/rtcOccluded1 over
// TBB; Embree packets run rtcIntersect16 on 4×4 pixel tiles with the COHERENT flag.
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
#include <embree3/rtcore.h>
#include <nlohmann/json.hpp>
#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include "backend/backend.h"
#include "bvh/embree_device.h"
#include "bvh/embree_scene.h"
#include "kernels/shared/geometry.h"
#include "kernels/shared/sampling.h"
#include "device/frame.h"
#include "render/renderer.h"
#include "device/scene_view.h"
#include "scene/loader.h"

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

struct RaySets {
    std::vector<float> primary, shadow, random;
};

RaySets make_rays(const Scene& scene, const SceneBuffers& b, Backend& embree, int w, int h) {
    TsFrame f = make_frame(scene.camera, w, h, 1, 1, b.light_count);
    RaySets r;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            ts::TsRay ray = ts::ts_camera_ray(&f, x, y, 0.5f, 0.5f);
            r.primary.insert(r.primary.end(), {ray.org.x, ray.org.y, ray.org.z, 0.0f, ray.dir.x, ray.dir.y,
                                               ray.dir.z, INFINITY});
        }
    std::vector<float> hits;
    embree.trace_closest(r.primary, hits);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::normal_distribution<float> g;
    const ts::TsSceneView sv = make_scene_view(b);
    for (size_t i = 0; i < r.primary.size() / TS_RAY_FLOATS; ++i) {
        const float* hi = &hits[TS_HIT_FLOATS * i];
        uint32_t prim;
        std::memcpy(&prim, &hi[TS_HIT_PRIM], 4);
        if (prim == TS_NO_HIT) continue;
        const float* pr = &r.primary[TS_RAY_FLOATS * i];
        ts::TsRay ray{ts::ts_f3_load(pr + TS_RAY_ORG), ts::ts_f3_load(pr + TS_RAY_DIR), 0.0f, INFINITY};
        ts::TsHit hit{hi[TS_HIT_T], hi[TS_HIT_U], hi[TS_HIT_V], prim};
        ts::TsSurface s = ts::ts_surface_at(&sv, ray, hit);
        ts::float3 o = ts::ts_offset_ray_origin(s.origin, s.geo_normal, s.pos_scale);
        ts::TsLightSample ls = ts::ts_sample_light(b.lights.data(), b.light_cdf.data(), b.light_count, u(rng),
                                                   u(rng), u(rng));
        ts::float3 d = ls.position - o;
        r.shadow.insert(r.shadow.end(), {o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, 0.99999f});
        ts::float3 dr = ts::normalize(ts::make_float3(g(rng), g(rng), g(rng)));
        if (ts::dot(dr, s.geo_normal) < 0.0f) dr = -dr;  // leave the surface on its lit side
        r.random.insert(r.random.end(), {o.x, o.y, o.z, 0.0f, dr.x, dr.y, dr.z, INFINITY});
    }
    return r;
}

// rtcIntersect16 over 4×4 tiles of the primary rays (row-major w × h).
void trace_packets(RTCScene scene, const std::vector<float>& rays, int w, int h) {
    const int tiles_x = w / 4, tiles_y = h / 4;
    tbb::parallel_for(tbb::blocked_range<int>(0, tiles_x * tiles_y, 16), [&](const tbb::blocked_range<int>& r) {
        set_ftz_daz();
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        alignas(64) RTCRayHit16 rh;
        alignas(64) int valid[16];
        for (int t = r.begin(); t < r.end(); ++t) {
            const int tx = t % tiles_x, ty = t / tiles_x;
            for (int k = 0; k < 16; ++k) {
                const float* ray = &rays[TS_RAY_FLOATS * (size_t(ty * 4 + k / 4) * w + tx * 4 + k % 4)];
                rh.ray.org_x[k] = ray[TS_RAY_ORG + 0];
                rh.ray.org_y[k] = ray[TS_RAY_ORG + 1];
                rh.ray.org_z[k] = ray[TS_RAY_ORG + 2];
                rh.ray.tnear[k] = ray[TS_RAY_TMIN];
                rh.ray.dir_x[k] = ray[TS_RAY_DIR + 0];
                rh.ray.dir_y[k] = ray[TS_RAY_DIR + 1];
                rh.ray.dir_z[k] = ray[TS_RAY_DIR + 2];
                rh.ray.tfar[k] = ray[TS_RAY_TMAX];
                rh.ray.time[k] = 0.0f;
                rh.ray.mask[k] = 0xffffffffu;
                rh.ray.flags[k] = 0;
                rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
                valid[k] = -1;
            }
            rtcIntersect16(valid, scene, &ctx, &rh);
        }
    });
}

std::string machine_name() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    return "unknown CPU";
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Tessera ray-throughput and frame-time benchmark"};
    std::string scene_path = std::string(TESSERA_SCENES_DIR) + "/sibenik.json", out_dir = "bench/results";
    std::string device;
    int repeats = 7, size = 512;
    app.add_option("--scene", scene_path);
    app.add_option("--device", device, "OpenCL device");
    app.add_option("--repeats", repeats)->capture_default_str();
    app.add_option("--size", size, "image width and height")->capture_default_str();
    app.add_option("--out", out_dir, "directory for ray_bench.json and ray_bench.md")->capture_default_str();
    CLI11_PARSE(app, argc, argv);

    Scene scene = load_scene(scene_path, make_data_path(std::nullopt));
    SceneBuffers b = make_scene_buffers(scene);
    EffectPlan plan = plan_effects(scene);
    auto em = make_backend({BackendKind::Embree, ""}, b, plan);
    auto cl = make_backend({BackendKind::OpenCL, device}, b, plan);
    RTCScene packet_scene = build_embree_scene(b);
    RaySets rays = make_rays(scene, b, *em, size, size);

    nlohmann::json j;
    j["machine"] = {{"cpu", machine_name()}, {"threads", tbb::info::default_concurrency()},
                    {"opencl", cl->description()}, {"embree", em->description()}};
    j["scene"] = scene.name;
    j["triangles"] = scene.triangle_count();
    j["size"] = size;
    j["repeats"] = repeats;
    std::vector<float> hits;
    std::vector<uint32_t> occ;
    cl->trace_closest(rays.primary, hits);  // warm-up: builds (or loads) the trace program
    cl->trace_occluded(rays.shadow, occ);
    auto mrays = [](size_t n, double s) { return n / s * 1e-6; };
    struct Row {
        std::string name;
        size_t n;
        double cl, em, packets;
    };
    std::vector<Row> rows;
    auto run_set = [&](const char* name, const std::vector<float>& r, bool closest) {
        Row row{name, r.size() / TS_RAY_FLOATS, 0, 0, 0};
        if (closest) {
            row.cl = mrays(row.n, median_seconds(repeats, [&] { cl->trace_closest(r, hits); }));
            row.em = mrays(row.n, median_seconds(repeats, [&] { em->trace_closest(r, hits); }));
        } else {
            row.cl = mrays(row.n, median_seconds(repeats, [&] { cl->trace_occluded(r, occ); }));
            row.em = mrays(row.n, median_seconds(repeats, [&] { em->trace_occluded(r, occ); }));
        }
        rows.push_back(row);
        std::fprintf(stderr, "%-8s %8zu rays  OpenCL %6.2f  Embree %6.2f Mrays/s  ratio %.2f\n", name, row.n, row.cl,
                     row.em, row.cl / row.em);
    };
    run_set("primary", rays.primary, true);
    rows.back().packets = mrays(rows.back().n, median_seconds(repeats, [&] {
                                    trace_packets(packet_scene, rays.primary, size, size);
                                }));
    run_set("shadow", rays.shadow, false);
    run_set("random", rays.random, true);
    for (const auto& r : rows)
        j["rays"][r.name] = {{"count", r.n}, {"opencl_mrays_s", r.cl}, {"embree_single_mrays_s", r.em},
                             {"embree_packet16_mrays_s", r.packets}, {"opencl_over_embree", r.cl / r.em}};

    RenderSettings rs;
    rs.width = rs.height = size;
    rs.shadow_samples = 16;
    rs.spp = static_cast<uint32_t>(repeats);
    RenderStats scl, sem;
    render_frame(*cl, scene, b, rs, &scl);
    render_frame(*em, scene, b, rs, &sem);
    j["direct_frame"] = {{"shadow_samples", 16}, {"opencl_ms", 1e3 * scl.median_pass_seconds},
                         {"embree_ms", 1e3 * sem.median_pass_seconds},
                         {"opencl_over_embree_speed", sem.median_pass_seconds / scl.median_pass_seconds}};
    std::fprintf(stderr, "direct %dx%d, 16 shadow samples: OpenCL %.1f ms, Embree %.1f ms per frame\n", size, size,
                 1e3 * scl.median_pass_seconds, 1e3 * sem.median_pass_seconds);
    rtcReleaseScene(packet_scene);

    fs::create_directories(out_dir);
    std::ofstream(fs::path(out_dir) / "ray_bench.json") << j.dump(2) << "\n";
    std::ofstream md(fs::path(out_dir) / "ray_bench.md");
    md << "# Ray throughput and `direct` frame time: " << scene.name << ", " << size << "x" << size << "\n\n"
       << "Machine: " << j["machine"]["cpu"].get<std::string>() << ", " << tbb::info::default_concurrency()
       << " threads. OpenCL: " << cl->description() << ". Medians of " << repeats << " runs.\n\n"
       << "| rays | count | OpenCL (Mrays/s) | Embree rtcIntersect1/Occluded1 (Mrays/s) | OpenCL / Embree | "
          "Embree rtcIntersect16 (Mrays/s) |\n|---|---|---|---|---|---|\n";
    char buf[256];
    for (const auto& r : rows) {
        std::snprintf(buf, sizeof buf, "| %s | %zu | %.2f | %.2f | %.2f | %s |\n", r.name.c_str(), r.n, r.cl, r.em,
                      r.cl / r.em, r.packets > 0 ? std::to_string(r.packets).substr(0, 5).c_str() : "-");
        md << buf;
    }
    std::snprintf(buf, sizeof buf,
                  "\n`direct`, 16 shadow samples, 1 spp: OpenCL %.1f ms, Embree %.1f ms per frame "
                  "(Embree time / OpenCL time = %.2f).\n",
                  1e3 * scl.median_pass_seconds, 1e3 * sem.median_pass_seconds,
                  sem.median_pass_seconds / scl.median_pass_seconds);
    md << buf;
    return 0;
}
