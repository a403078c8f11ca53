// One tic frame for the tests of the cache's record–VPL kernels: frame 12 of the animated
// Cornell box (the cube mid-way across the floor), 40², 64 light paths, the cache built on
// Embree, and the visibility of every record–VPL pair as the Embree pair kernel finds it.
#pragma once
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "backend/backend.h"
#include "device/effect_plan.h"
#include "device/scene_buffers.h"
#include "gi/ic_gather.h"
#include "gi/ic_passes.h"
#include "gi/irradiance_cache.h"
#include "kernels/shared/vpl.h"
#include "render/renderer.h"
#include "scene/loader.h"

namespace tessera::test {

struct IcTestFrame {
    Scene scene;
    SceneBuffers buffers;
    EffectPlan plan;
    RenderSettings settings;
    std::unique_ptr<Backend> embree;  // holds references to buffers: the frame is not copied

    IcTestFrame()
        : scene(scene_at_frame(load_scene(default_scene_path().parent_path() / "cornell-box-animated.json",
                                          make_data_path(std::nullopt)),
                               12)),
          buffers(make_scene_buffers(scene)),
          plan(plan_effects(scene)) {
        settings.method = Method::Tic;
        settings.spp = 1;
        settings.width = settings.height = 40;
        settings.igi.tile = 1;
        settings.ic.paths = 64;
        settings.ic.temporal = true;
        settings.ic_state = std::make_shared<IcPassCaches>(settings.ic, scene.objects);
        embree = make_backend({BackendKind::Embree, ""}, buffers, plan);
        render_frame(*embree, scene, buffers, settings);
    }
    IcTestFrame(const IcTestFrame&) = delete;
    IcTestFrame& operator=(const IcTestFrame&) = delete;

    const std::vector<IcRecord>& records() const { return settings.ic_state->pass(0).cache().records(); }
    const std::vector<float>& vpls() const { return settings.ic_state->pass(0).vpls(); }
    size_t vpl_count() const { return vpls().size() / TS_VPL_FLOATS; }

    /// Every (record, VPL) pair in order (TS_IC_PAIR_WORDS each), its code from the Embree
    /// pair kernel with bound b, and the records' rows packed as the cache packs them
    /// (TS_IC_VISIBLE_WORDS(vpl_count()) uints a record; visible = TS_IC_PAIR_VISIBLE).
    void trace_all_pairs(float b, std::vector<uint32_t>& pairs, std::vector<uint32_t>& hits,
                         std::vector<uint32_t>& rows) const {
        const size_t nv = vpl_count(), words = TS_IC_VISIBLE_WORDS(nv);
        pairs.clear();
        for (uint32_t i = 0; i < records().size(); ++i)
            for (uint32_t j = 0; j < nv; ++j) pairs.insert(pairs.end(), {i, j});
        ic_set_record_inputs(*embree, records(), vpls());
        ic_trace_pairs(*embree, b, pairs, hits);
        rows.assign(records().size() * words, 0u);
        for (size_t i = 0; i < records().size(); ++i)
            ic_pack_visible(reinterpret_cast<const int32_t*>(&hits[i * nv]), nv, &rows[i * words]);
    }

    /// Whether triangle `prim` meets the shadow ray of the pair (record, vpl) with bound b
    /// (the ray ts_ic_pair_ray builds): Möller–Trumbore in double, barycentrics and t
    /// within `slack` (relative) of their ranges, so that a watertight hit on a shared
    /// edge counts for either triangle; a negative `slack` asks for a hit that far inside
    /// them. False for a `prim` that is no triangle.
    bool pair_ray_meets(float b, uint32_t record, uint32_t vpl, uint32_t prim, double slack = 1e-5) const {
        if (prim >= buffers.triangle_count) return false;
        const ts::TsSurface s = ic_record_surface(records()[record]);
        ts::TsRay ray;
        if (ts::ts_vpl_geometry(&s, &vpls()[size_t(TS_VPL_FLOATS) * vpl], b, buffers.medium[TS_MEDIUM_G], &ray) <= 0.0f)
            return false;
        const float* t = &buffers.tri_pos[9 * size_t(prim)];
        const double o[3] = {ray.org.x, ray.org.y, ray.org.z}, d[3] = {ray.dir.x, ray.dir.y, ray.dir.z};
        double e1[3], e2[3], sv[3];
        for (int k = 0; k < 3; ++k) e1[k] = t[3 + k] - t[k], e2[k] = t[6 + k] - t[k], sv[k] = o[k] - t[k];
        auto cross = [](const double* a, const double* c, double* r) {
            r[0] = a[1] * c[2] - a[2] * c[1], r[1] = a[2] * c[0] - a[0] * c[2], r[2] = a[0] * c[1] - a[1] * c[0];
        };
        auto dot = [](const double* a, const double* c) { return a[0] * c[0] + a[1] * c[1] + a[2] * c[2]; };
        double p[3], q[3];
        cross(d, e2, p);
        const double det = dot(e1, p);
        if (det == 0.0) return false;
        cross(sv, e1, q);
        const double u = dot(sv, p) / det, v = dot(d, q) / det, tt = dot(e2, q) / det;
        return u >= -slack && v >= -slack && u + v <= 1.0 + slack && tt >= ray.tmin * (1.0 - slack) &&
               tt <= ray.tmax * (1.0 + slack);
    }

    /// Knife-edge pairs, which two correct backends may class apart when their rays differ
    /// by a few ulps (a GPU's built-ins, such as dot, round apart from C++); a traversal
    /// that drops or adds a triangle the ray crosses well inside meets neither test.
    /// pair_faces_on_edge: a facing cosine of the pair (record, vpl) within `slack` of 0
    /// and not 0 (in double from the shared layout), for facing against visible or
    /// occluded. A float cosine's products round by ~6e-8 each, so two devices' cosines
    /// differ by a few 1e-7: 1e-6 covers that. An exact 0 (a pair on one axis-aligned
    /// wall) is 0 on every device.
    bool pair_faces_on_edge(uint32_t record, uint32_t vpl, double slack = 1e-6) const {
        const ts::TsSurface s = ic_record_surface(records()[record]);
        const float* v = &vpls()[size_t(TS_VPL_FLOATS) * vpl];
        const double w[3] = {double(v[TS_VPL_POSITION]) - s.position.x, double(v[TS_VPL_POSITION + 1]) - s.position.y,
                             double(v[TS_VPL_POSITION + 2]) - s.position.z};
        const double len = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
        auto cosine = [&](double x, double y, double z) { return (x * w[0] + y * w[1] + z * w[2]) / len; };
        for (double c : {cosine(s.shading_normal.x, s.shading_normal.y, s.shading_normal.z),
                         cosine(s.geo_normal.x, s.geo_normal.y, s.geo_normal.z),
                         cosine(v[TS_VPL_NORMAL], v[TS_VPL_NORMAL + 1], v[TS_VPL_NORMAL + 2])})
            if (c != 0.0 && std::fabs(c) < slack) return true;
        return false;
    }

    /// pair_ray_only_grazes: no triangle meets the pair's shadow ray with barycentrics and
    /// t `slack` inside their ranges, and some triangle meets it within `slack` outside
    /// them (pair_ray_meets), for visible against occluded.
    bool pair_ray_only_grazes(float b, uint32_t record, uint32_t vpl, double slack = 1e-5) const {
        bool grazed = false;
        for (uint32_t prim = 0; prim < buffers.triangle_count; ++prim) {
            if (pair_ray_meets(b, record, vpl, prim, -slack)) return false;
            grazed = grazed || pair_ray_meets(b, record, vpl, prim, slack);
        }
        return grazed;
    }
};

}  // namespace tessera::test
