#include "gi/light_paths.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "gi/halton.h"
#include "kernels/shared/layout_light_path.h"
#include "kernels/shared/light_path.h"
#include "kernels/shared/rng.h"
#include "device/frame.h"
#include "device/ray_records.h"
#include "device/scene_buffers.h"
#include "device/scene_view.h"

namespace tessera {
namespace {

using ts::float3;

// A path in flight: what it left so far, and its state (shared/light_path.h).
struct InFlight {
    LightPath* path;
    ts::TsLightPathState state;
};

ts::TsLightPathState initial_state(const LightPath& p) {
    ts::TsLightPathState st{};
    st.index = p.index;
    st.set = p.set;
    st.weight = p.weight;
    return st;
}

void append(std::vector<float>& records, const float* record, int floats) {
    records.insert(records.end(), record, record + floats);
}

// The Halton points of a scramble and dimension count, built once per thread and kept (the
// table, a shuffle per dimension, ~100k digits at 64 bounces, is the same every frame): a
// few entries, as a frame may ask for two tables (the kernel's and, for paths that
// overflow its slots, the host's).
std::shared_ptr<const ScrambledHalton> halton_for(int dims, uint32_t scramble) {
    struct Entry {
        int dims;
        uint32_t scramble;
        std::shared_ptr<const ScrambledHalton> halton;
    };
    thread_local std::vector<Entry> cache;
    for (const Entry& e : cache)
        if (e.dims == dims && e.scramble == scramble) return e.halton;
    if (cache.size() == 4) cache.erase(cache.begin());
    cache.push_back({dims, scramble, std::make_shared<const ScrambledHalton>(dims, scramble)});
    return cache.back().halton;
}

uint32_t scramble_of(const LightPathSettings& settings) {
    // The Halton digits and the medium events' generator share one scramble of the seed.
    return settings.halton_seed ^ light_path_seed_mix(settings.seed);
}

// The far roulette's region for light paths (ts_far_importance, shared/medium.h): the
// bounds of the scene's surfaces in every frame of its animation (SceneBuffers::reach),
// their diagonal the margin (far_region_of). The same region every frame keeps a path
// with the same Halton point and hits the same path, as tic's update relies on.
ts::TsFarRegion far_region(const SceneBuffers& scene) {
    return far_region_of(scene.reach.lo, scene.reach.hi);
}

void put_float(float f, uint32_t* word) { std::memcpy(word, &f, 4); }

// The light-path table's header (layout_light_path.h) for `settings` in `scene`: what
// ts_light_path_params reads.
std::array<uint32_t, TS_LPT_HALTON> light_path_header(const LightPathSettings& settings, const SceneBuffers& scene) {
    std::array<uint32_t, TS_LPT_HALTON> h{};
    h[TS_LPT_SCRAMBLE] = scramble_of(settings);
    h[TS_LPT_MAX_BOUNCES] = settings.max_bounces;
    h[TS_LPT_FLAGS] = (settings.medium_scattering ? TS_LPT_MEDIUM_SCATTERING : 0u) |
                      (settings.ray_lights ? TS_LPT_RAY_LIGHTS : 0u);
    put_float(settings.inv_paths, &h[TS_LPT_INV_PATHS]);
    const ts::TsFarRegion r = far_region(scene);
    const float box[6] = {r.lo.x, r.lo.y, r.lo.z, r.hi.x, r.hi.y, r.hi.z};
    for (int i = 0; i < 3; ++i) {
        put_float(box[i], &h[TS_LPT_REGION_LO + i]);
        put_float(box[3 + i], &h[TS_LPT_REGION_HI + i]);
    }
    put_float(r.margin, &h[TS_LPT_REGION_MARGIN]);
    return h;
}

void clear(LightPath& p) {
    p.vpls.clear();
    p.vrls.clear();
    p.segments.clear();
    p.light = 0;
}

// Path p's segment of `bounce` from the hit `hit_floats` of its ray (ts_light_path_segment):
// appends what it leaves to p's records and returns ts_light_path_segment's flags.
uint32_t segment(const ts::TsSceneView& sv, const ts::TsMedium& med, const ScrambledHalton& halton,
                 const ts::TsLightPathParams& lp, const LightPathSettings& settings, uint32_t bounce,
                 const float* hit_floats, InFlight& p) {
    const ts::TsRay before = p.state.ray;
    const ts::TsHit hit = load_hit(hit_floats);
    ts::TsLightPathEvent ev;
    const uint32_t what = ts::ts_light_path_segment(&sv, &med, halton.table().data(), &lp, bounce, hit, &p.state, &ev);
    if (settings.segments)
        p.path->segments.push_back(PathSegment{{before.org.x, before.org.y, before.org.z},
                                               {before.dir.x, before.dir.y, before.dir.z}, ev.seg_t, ev.seg_prim});
    if (what & TS_LIGHT_PATH_VRL) append(p.path->vrls, ev.vrl, TS_VRL_FLOATS);
    if (what & TS_LIGHT_PATH_VPL) append(p.path->vpls, ev.vpl, TS_VPL_FLOATS);
    return what;
}

// Every bounce of every path batched through Backend::trace_closest, each segment through
// ts_light_path_segment.
uint64_t trace_batched(Backend& backend, const SceneBuffers& scene, const LightPathSettings& settings,
                       std::vector<LightPath>& paths) {
    const ts::TsSceneView sv = make_scene_view(scene);
    const ts::TsMedium med = ts::ts_medium_load(scene.medium.data());
    const uint32_t scramble = scramble_of(settings);
    const std::shared_ptr<const ScrambledHalton> owner =
        halton_for(5 + 3 * static_cast<int>(std::min(settings.max_bounces, kHaltonLightPathBounces)), scramble);
    const ScrambledHalton& halton = *owner;
    const ts::TsLightPathParams lp = ts::ts_light_path_params(light_path_header(settings, scene).data());
    std::vector<InFlight> live;
    for (LightPath& p : paths) {
        clear(p);
        InFlight f{&p, initial_state(p)};
        if (scene.light_count > 0 && ts::ts_light_path_begin(&sv, halton.table().data(), &f.state, &p.light))
            live.push_back(f);
    }
    uint64_t traced = 0;
    std::vector<float> rays, hits;
    for (uint32_t bounce = 0; bounce < settings.max_bounces && !live.empty(); ++bounce) {
        rays.assign(TS_RAY_FLOATS * live.size(), 0.0f);
        for (size_t i = 0; i < live.size(); ++i) store_ray(live[i].state.ray, &rays[TS_RAY_FLOATS * i]);
        backend.trace_closest(rays, hits);
        traced += live.size();
        // Each path's segment in parallel (a path writes only its own records); the
        // survivors then keep their order, so the VPLs do too.
        std::vector<uint32_t> what(live.size());
        tbb::parallel_for(tbb::blocked_range<size_t>(0, live.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i < r.end(); ++i) what[i] = segment(sv, med, halton, lp, settings, bounce,
                                                                            &hits[TS_HIT_FLOATS * i], live[i]);
        });
        std::vector<InFlight> alive;
        for (size_t i = 0; i < live.size(); ++i)
            if (what[i] & TS_LIGHT_PATH_CONTINUES) alive.push_back(live[i]);
        live.swap(alive);
    }
    return traced;
}

// A path's part of the light-path kernel's output: its header (TS_LP_STATUS .. TS_LP_VRLS)
// and its VPL and ray-light records, each in path order.
struct PathOutput {
    const float* head;
    const float* vpls;
    const float* vrls;
};

// The output of `paths` paths read back whole: stride floats a path, slots and all.
std::vector<PathOutput> whole_output(const std::vector<float>& out, size_t paths, size_t stride) {
    std::vector<PathOutput> o(paths);
    for (size_t i = 0; i < paths; ++i) {
        const float* at = &out[stride * i];
        o[i] = {at, at + TS_LP_VPL, at + TS_LP_VRL};
    }
    return o;
}

// The output of `paths` paths (stride floats each) kept as input LightPathOut, read back by
// KernelId::LightPathGather: the headers, then the records of the paths that did not
// overflow (`heads` and `records` hold what was read; the spans point into them).
std::vector<PathOutput> gathered_output(Backend& backend, const TsFrame& frame, size_t paths, size_t stride,
                                        std::vector<float>& heads, std::vector<float>& records) {
    std::vector<uint32_t> at(paths);
    for (size_t i = 0; i < paths; ++i) at[i] = static_cast<uint32_t>(stride * i);
    backend.launch_items(KernelId::LightPathGather, frame, at, heads);
    std::vector<size_t> first(paths + 1, 0);
    at.clear();
    for (size_t i = 0; i < paths; ++i) {
        const float* h = &heads[TS_LP_GATHER_FLOATS * i];
        if (h[TS_LP_STATUS] == 0.0f) {
            for (uint32_t v = 0; v < static_cast<uint32_t>(h[TS_LP_VPLS]); ++v)
                at.push_back(static_cast<uint32_t>(stride * i + TS_LP_VPL + size_t(TS_VPL_FLOATS) * v));
            for (uint32_t v = 0; v < static_cast<uint32_t>(h[TS_LP_VRLS]); ++v)
                at.push_back(static_cast<uint32_t>(stride * i + TS_LP_VRL + size_t(TS_VRL_FLOATS) * v));
        }
        first[i + 1] = at.size();
    }
    backend.launch_items(KernelId::LightPathGather, frame, at, records);
    // No records (paths that left none): any valid pointer, as nothing is read through it.
    const float* base = records.empty() ? heads.data() : records.data();
    std::vector<PathOutput> o(paths);
    for (size_t i = 0; i < paths; ++i) {
        const float* h = &heads[TS_LP_GATHER_FLOATS * i];
        const float* r = base + (records.empty() ? 0 : TS_LP_GATHER_FLOATS * first[i]);
        o[i] = {h, r, h[TS_LP_STATUS] == 0.0f ? r + size_t(TS_VPL_FLOATS) * static_cast<size_t>(h[TS_LP_VPLS]) : r};
    }
    return o;
}

}  // namespace

uint32_t light_path_seed_mix(uint32_t seed) { return ts::ts_pcg_hash(seed) ^ ts::ts_pcg_hash(1u); }

// The kernel's table is a prefix of the host's (ScrambledHalton draws its dimensions in
// order): a path overflowing the kernel's slots is traced again on the host with the same
// numbers only while every bounce the kernel traces is a Halton one there too.
static_assert(TS_LP_MAX_BOUNCES <= kHaltonLightPathBounces, "kernel bounces past the host's Halton ones");

uint64_t trace_light_paths_in_kernel(Backend& backend, const SceneBuffers& scene, const LightPathSettings& settings,
                                     std::vector<LightPath>& paths) {
    const uint32_t scramble = scramble_of(settings);
    const uint32_t bounces = std::min<uint32_t>(settings.max_bounces, TS_LP_MAX_BOUNCES);
    // The kernel's table holds only the dimensions of the segments it traces; a path that
    // needs more overflows (max_bounces > TS_LP_MAX_BOUNCES) and is traced here.
    const std::array<uint32_t, TS_LPT_HALTON> header = light_path_header(settings, scene);
    std::vector<uint32_t> table(header.begin(), header.end());
    const std::shared_ptr<const ScrambledHalton> halton = halton_for(5 + 3 * static_cast<int>(bounces), scramble);
    table.insert(table.end(), halton->table().begin(), halton->table().end());
    backend.set_input_if_changed(KernelInput::LightPathTable, table);
    std::vector<uint32_t> items(TS_LP_ITEM_WORDS * paths.size());
    for (size_t i = 0; i < paths.size(); ++i) {
        uint32_t* it = &items[TS_LP_ITEM_WORDS * i];
        it[TS_LP_ITEM_INDEX_LO] = static_cast<uint32_t>(paths[i].index);
        it[TS_LP_ITEM_INDEX_HI] = static_cast<uint32_t>(paths[i].index >> 32);
        it[TS_LP_ITEM_SET] = paths[i].set;
        std::memcpy(&it[TS_LP_ITEM_WEIGHT], &paths[i].weight, 4);
    }
    std::vector<float> out;
    TsFrame frame{};
    frame.light_count = scene.light_count;  // the kernels' TsSceneView takes it from the frame
    // Ray-light slots only where paths leave ray lights: a third less to read back without.
    const bool ray_lights = settings.medium_scattering && settings.ray_lights && scene.medium[TS_MEDIUM_PRESENT] != 0.0f;
    const KernelId k = ray_lights ? KernelId::LightPathsMedia : KernelId::LightPaths;
    const size_t stride = static_cast<size_t>(kernel_info(k).out_floats);
    // The gather's offsets are uints: a launch past 2^32 floats reads back whole.
    const bool gather = backend.gathers_light_paths() && stride * paths.size() <= UINT32_MAX;
    std::vector<float> heads;
    std::vector<PathOutput> output;
    if (gather) {
        backend.launch_items_into(k, frame, items, KernelInput::LightPathOut);
        output = gathered_output(backend, frame, paths.size(), stride, heads, out);
    } else {
        backend.launch_items(k, frame, items, out);
        output = whole_output(out, paths.size(), stride);
    }
    uint64_t traced = 0;
    std::vector<LightPath> again;
    std::vector<size_t> again_at;
    for (size_t i = 0; i < paths.size(); ++i) {
        LightPath& p = paths[i];
        clear(p);
        const PathOutput& o = output[i];
        if (o.head[TS_LP_STATUS] != 0.0f) {
            again.push_back(untraced(p));
            again_at.push_back(i);
            continue;
        }
        p.light = static_cast<uint32_t>(o.head[TS_LP_LIGHT]);
        traced += static_cast<uint64_t>(o.head[TS_LP_RAYS]);
        p.vpls.assign(o.vpls, o.vpls + TS_VPL_FLOATS * static_cast<size_t>(o.head[TS_LP_VPLS]));
        p.vrls.assign(o.vrls, o.vrls + TS_VRL_FLOATS * static_cast<size_t>(o.head[TS_LP_VRLS]));
    }
    if (!again.empty()) {
        LightPathSettings host = settings;
        host.segments = false;
        traced += trace_batched(backend, scene, host, again);
        for (size_t j = 0; j < again.size(); ++j) paths[again_at[j]] = std::move(again[j]);
    }
    return traced;
}

uint64_t trace_light_paths(Backend& backend, const SceneBuffers& scene, const LightPathSettings& settings,
                           std::vector<LightPath>& paths) {
    if (!settings.segments && backend.traces_light_paths_in_kernel() && !paths.empty())
        return trace_light_paths_in_kernel(backend, scene, settings, paths);
    return trace_batched(backend, scene, settings, paths);
}

}  // namespace tessera
