// Packet dispatch for the Embree backend (embree_packets.h). Each lane runs the shared
// per-pixel code of kernels/shared/igi.h up to its links; the links are then traced one
// link index at a time across the 16 lanes (rtcOccluded16) and gathered per lane in link
// order, so every lane sums exactly what ts_igi_surface_set sums one ray at a time.
#include <algorithm>
#include <array>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "backend/embree_packets.h"
#include "bvh/embree_device.h"

// After the tracer (embree_packets.h includes it): the shared code calls it.
#include "kernels/shared/igi.h"

namespace tessera {
namespace {

constexpr int kLanes = TS_PACKET_LANES;  // rtcOccluded16: AVX-512 width, two AVX2 halves on this CPU

// Up to 16 lanes, each a surface seen through a pixel and the links it gathers.
struct Packet {
    int lanes = 0;
    std::array<ts::TsIgiView, kLanes> view;
    std::array<ts::float3, kLanes> albedo;  // looked up once: a textured albedo costs a pow per texel
    std::array<uint32_t, kLanes> set{}, mask{}, links{};  // links = 0: nothing to gather
    std::array<ts::TsIgiGather, kLanes> gather;
};

// Traces link j of every lane that has one as one packet, for j = 0 .. the most links of
// any lane, and adds each lane's visible links to its gather in link order. `coherent`:
// the lanes' surfaces lie close together (a pixel block), so Embree's coherent mode pays;
// for lanes scattered over the image it costs (docs/ray-batches.md §3).
void gather_links_per_lane(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame, Packet& p,
                           bool coherent) {
    const ts::TsMedium med = ts::ts_medium_load(sv.medium);
    uint32_t most = 0;
    for (int i = 0; i < p.lanes; ++i) most = std::max(most, p.links[i]);
    std::array<ts::TsIgiLink, kLanes> link;
    std::array<ts::TsRay, kLanes> rays{};  // zeroed: a skipped lane is never traced
    for (uint32_t j = 0; j < most; ++j) {
        std::array<int, kLanes> valid{};
        bool any = false;
        for (int i = 0; i < p.lanes; ++i) {
            if (j >= p.links[i] || !ts::ts_igi_link(&sv, &frame, &p.view[i].s, p.set[i], p.mask[i], j, &link[i]))
                continue;
            valid[i] = -1;
            rays[i] = link[i].shadow;
            any = true;
        }
        if (!any) continue;
        const uint32_t blocked = ts::ts_trace_occluded16(&tracer, rays.data(), valid.data(), coherent);
        for (int i = 0; i < p.lanes; ++i)
            if (valid[i] && !(blocked >> i & 1u)) ts::ts_igi_gather_add(&p.gather[i], &sv, &med, &link[i]);
    }
}

// The lanes' surfaces as a structure of arrays (the fields ts_vpl_geometry reads), and
// their E_id sums, for the VPL links of a packet whose lanes share one sample set.
struct LaneSurfaces {
    alignas(64) float position[3][kLanes], geo_normal[3][kLanes], shading_normal[3][kLanes], origin[3][kLanes];
    alignas(64) float pos_scale[kLanes];
    alignas(64) float id[3][kLanes];
};

// Lane i's surface; a lane without links gets the surface of lane `stand_in`, so that
// every lane's ray is finite (Embree may read rays of masked-off lanes).
void lane_surfaces(const Packet& p, int stand_in, LaneSurfaces& ls) {
    for (int i = 0; i < kLanes; ++i) {
        const ts::TsSurface& s = p.view[i < p.lanes && p.links[i] > 0 ? i : stand_in].s;
        const ts::float3 f[4] = {s.position, s.geo_normal, s.shading_normal, s.origin};
        float(*dst[4])[kLanes] = {ls.position, ls.geo_normal, ls.shading_normal, ls.origin};
        for (int a = 0; a < 4; ++a) {
            dst[a][0][i] = f[a].x;
            dst[a][1][i] = f[a].y;
            dst[a][2][i] = f[a].z;
        }
        ls.pos_scale[i] = s.pos_scale;
        ls.id[0][i] = ls.id[1][i] = ls.id[2][i] = 0.0f;
    }
}

// Lane i's surface, with the fields ts_vpl_geometry does not read set to constants (not
// value-initialised: GCC then clears the struct with a memset and no longer vectorises).
ts::TsSurface lane_surface(const LaneSurfaces& ls, int i) {
    ts::TsSurface s;
    s.uv = ts::make_float2(0.0f, 0.0f);
    s.material = 0;
    s.front_face = 1;
    s.uv_footprint = 0.0f;
    s.position = ts::make_float3(ls.position[0][i], ls.position[1][i], ls.position[2][i]);
    s.geo_normal = ts::make_float3(ls.geo_normal[0][i], ls.geo_normal[1][i], ls.geo_normal[2][i]);
    s.shading_normal = ts::make_float3(ls.shading_normal[0][i], ls.shading_normal[1][i], ls.shading_normal[2][i]);
    s.origin = ts::make_float3(ls.origin[0][i], ls.origin[1][i], ls.origin[2][i]);
    s.pos_scale = ls.pos_scale[i];
    return s;
}

// One VPL against all 16 lanes: its clamped geometry terms g and shadow rays (written
// into r), by the shared ts_vpl_geometry. The loop is branch-free and vectorises (16
// lanes of SIMD for the per-link math that cost 40% of an Embree igi frame on the Cornell
// box); `vpl` is a restrict-qualified local copy, so GCC sees it as invariant.
template <bool Medium>
void vpl_links_loop(const LaneSurfaces& __restrict ls, const float (&__restrict vpl)[TS_VPL_FLOATS], float b,
                    float hg, float* __restrict g, RTCRay16& __restrict r) {
    if (ts::ts_vpl_in_medium(vpl) != Medium) __builtin_unreachable();  // lets GCC fold the kind tests
    for (int i = 0; i < kLanes; ++i) {
        const ts::TsSurface s = lane_surface(ls, i);
        ts::TsRay sh;
        g[i] = ts::ts_vpl_geometry(&s, vpl, b, hg, &sh);
        r.org_x[i] = sh.org.x;
        r.org_y[i] = sh.org.y;
        r.org_z[i] = sh.org.z;
        r.dir_x[i] = sh.dir.x;
        r.dir_y[i] = sh.dir.y;
        r.dir_z[i] = sh.dir.z;
        r.tnear[i] = sh.tmin;
        r.tfar[i] = sh.tmax;
    }
}

// vpl_links_loop, inlined once for surface and once for medium VPLs: in each copy the
// VPL kind is known, so the vector loop computes only that kind's emission factor (the
// Henyey–Greenstein phase for a medium VPL, a cosine otherwise).
[[gnu::noinline]] void vpl_links(const LaneSurfaces& __restrict ls, const float (&__restrict vpl)[TS_VPL_FLOATS],
                                 float b, float hg, float* __restrict g, RTCRay16& __restrict r) {
    if (ts::ts_vpl_in_medium(vpl))
        vpl_links_loop<true>(ls, vpl, b, hg, g, r);
    else
        vpl_links_loop<false>(ls, vpl, b, hg, g, r);
}

// Lane i's shadow ray back out of the packet (unchanged by Embree where unoccluded).
ts::TsRay lane_ray(const RTCRay16& r, int i) {
    ts::TsRay ray;
    ray.org = ts::make_float3(r.org_x[i], r.org_y[i], r.org_z[i]);
    ray.dir = ts::make_float3(r.dir_x[i], r.dir_y[i], r.dir_z[i]);
    ray.tmin = r.tnear[i];
    ray.tmax = r.tfar[i];
    return ray;
}

// Adds the VPL to the E_id sums of the lanes with seen[i] = -1 (all bits: lane i's link
// is visible; 0 otherwise), by ts_vpl_gather_term/ts_vpl_gather_add. Without a medium the
// transmittance is 1 and the loop vectorises: a hidden lane's G' is masked to +0 with
// bits (a select or a 0/1 factor keeps GCC 12 from vectorising), so it adds C·0 = +0 to
// a sum that is >= +0: the sums are bit for bit those of adding visible links only (C is
// finite). With a medium, each lane's transmittance is an exp along its ray.
[[gnu::noinline]] void vpl_gather(LaneSurfaces& __restrict ls, const float (&__restrict vpl)[TS_VPL_FLOATS], const ts::TsMedium& med,
                const float* __restrict g, const RTCRay16& r, const int* __restrict seen) {
    if (!med.present) {
        const ts::float3 clear = ts::make_float3(1.0f, 1.0f, 1.0f);  // ts_shadow_transmittance without a medium
        for (int i = 0; i < kLanes; ++i) {
            const ts::float3 t = ts::ts_vpl_gather_term(vpl, clear, ts::as_float(ts::as_int(g[i]) & seen[i]));
            ls.id[0][i] += t.x;
            ls.id[1][i] += t.y;
            ls.id[2][i] += t.z;
        }
        return;
    }
    for (int i = 0; i < kLanes; ++i) {
        if (!seen[i]) continue;
        ts::float3 sum = ts::make_float3(ls.id[0][i], ls.id[1][i], ls.id[2][i]);
        ts::ts_vpl_gather_add(&sum, vpl, &med, lane_ray(r, i), g[i]);
        ls.id[0][i] = sum.x, ls.id[1][i] = sum.y, ls.id[2][i] = sum.z;
    }
}

// gather_links for a packet whose lanes with links all share one sample set and component
// mask (a surface block): the same links in the same order, so the same sums, but each
// VPL link's math runs over the 16 lanes at once and its rays go straight into Embree's
// packet layout. The set's light samples (a few links) go through the per-lane code.
void gather_links_shared_set(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame, Packet& p,
                             int first, bool coherent) {
    const ts::TsMedium med = ts::ts_medium_load(sv.medium);
    const uint32_t k = p.set[first], mask = p.mask[first], links = p.links[first];
    const uint32_t m = ts::ts_igi_light_links(&sv, &frame, mask);
    alignas(64) RTCRay16 r;
    for (int i = 0; i < kLanes; ++i) {
        r.time[i] = 0.0f;
        r.mask[i] = 0xffffffffu;
        r.id[i] = static_cast<unsigned>(i);
        r.flags[i] = 0;
    }
    alignas(64) int valid[kLanes];
    auto trace = [&]() -> uint32_t {
        bool any = false;
        for (int i = 0; i < kLanes; ++i) any |= valid[i] != 0;
        return any ? ts::ts_occluded16(&tracer, r, valid, coherent) : 0u;
    };
    std::array<ts::TsIgiLink, kLanes> link;
    for (uint32_t j = 0; j < m; ++j) {
        for (int i = 0; i < kLanes; ++i) {
            valid[i] = i < p.lanes && p.links[i] > 0 &&
                               ts::ts_igi_link(&sv, &frame, &p.view[i].s, k, mask, j, &link[i])
                           ? -1
                           : 0;
            ts::ts_packet_set(r, i, valid[i] ? link[i].shadow : ts::TsRay{});  // a skipped lane is never traced
        }
        const uint32_t blocked = trace();
        for (int i = 0; i < p.lanes; ++i)
            if (valid[i] && !(blocked >> i & 1u)) ts::ts_igi_gather_add(&p.gather[i], &sv, &med, &link[i]);
    }
    LaneSurfaces ls;
    lane_surfaces(p, first, ls);
    alignas(64) float g[kLanes];
    float vpl[TS_VPL_FLOATS];
    for (uint32_t j = m; j < links; ++j) {
        const float* v = sv.vpls + size_t(sv.vpl_set_start[k] + (j - m)) * TS_VPL_FLOATS;
        std::copy(v, v + TS_VPL_FLOATS, vpl);
        vpl_links(ls, vpl, frame.igi_g_clamp, sv.medium[TS_MEDIUM_G], g, r);
        for (int i = 0; i < kLanes; ++i) valid[i] = i < p.lanes && p.links[i] > 0 && g[i] > 0.0f ? -1 : 0;
        const uint32_t blocked = trace();
        alignas(64) int seen[kLanes];
        for (int i = 0; i < kLanes; ++i) seen[i] = blocked >> i & 1u ? 0 : valid[i];
        vpl_gather(ls, vpl, med, g, r, seen);
    }
    for (int i = 0; i < p.lanes; ++i) p.gather[i].id = ts::make_float3(ls.id[0][i], ls.id[1][i], ls.id[2][i]);
}

// Each lane's links traced as packets and gathered in link order: a packet whose lanes
// (those with links) share one sample set and mask takes the SIMD path, others (AIS items
// of several sets) the per-lane one. Either way each lane sums exactly what
// ts_igi_surface_set sums one ray at a time.
void gather_links(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame, Packet& p,
                  bool coherent) {
    int first = -1;
    bool shared = true;
    for (int i = 0; i < p.lanes; ++i) {
        p.gather[i] = ts::ts_igi_gather_begin();
        if (p.links[i] == 0) continue;
        if (first < 0) first = i;
        shared &= p.set[i] == p.set[first] && p.mask[i] == p.mask[first] && p.links[i] == p.links[first];
    }
    if (first < 0) return;
    if (shared)
        gather_links_shared_set(sv, tracer, frame, p, first, coherent);
    else
        gather_links_per_lane(sv, tracer, frame, p, coherent);
}

// Lane i of p sees pixel (px, py); returns whether its camera path found a surface, and
// sets its links for set k and components `mask` (none when the albedo is black).
bool view_lane(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame, Packet& p, int i,
               uint32_t px, uint32_t py, uint32_t k, uint32_t mask) {
    p.view[i] = ts::ts_igi_view(&sv, &tracer, &frame, px, py);
    p.set[i] = k;
    p.mask[i] = mask;
    p.links[i] = 0;
    if (p.view[i].hit.prim == TS_NO_HIT) return false;
    p.albedo[i] = ts::ts_material_albedo(&sv, &p.view[i].s);
    if (ts::ts_max3(p.albedo[i]) > 0.0f)
        p.links[i] = ts::ts_igi_link_count(&sv, &frame, k, mask);
    return true;
}

// Block b of the frame (ts_packet_block, kernels/shared/geometry.h: the enumeration the
// OpenCL packet kernel uses too): 4×4 pixels of one sample set's sub-image.
void surface_block(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame, uint32_t b,
                   std::vector<float>& out) {
    uint32_t k, bx, by;
    if (!ts::ts_packet_block(&frame, b, &k, &bx, &by)) return;
    Packet p;
    std::array<float*, kLanes> o{};
    std::array<bool, kLanes> hit{};
    for (uint32_t lane = 0; lane < kLanes; ++lane) {
        uint32_t px, py;
        if (!ts::ts_packet_block_pixel(&frame, k, bx, by, lane, &px, &py)) continue;
        const int i = p.lanes++;
        o[i] = &out[(size_t(py) * frame.width + px) * TS_IGI_SURF_FLOATS];
        ts::ts_igi_surface_clear(o[i]);
        hit[i] = view_lane(sv, tracer, frame, p, i, px, py, ts::ts_igi_set(px, py, frame.igi_tile),
                           frame.igi_components);
    }
    gather_links(sv, tracer, frame, p, true);
    for (int i = 0; i < p.lanes; ++i) {
        if (!hit[i]) continue;
        ts::float3 e_ss, e_id;
        float visible;
        ts::ts_igi_gather_end(&p.gather[i], &frame, &e_ss, &e_id, &visible);
        const ts::TsSurface& s = p.view[i].s;
        ts::ts_igi_surface_store(&p.view[i], p.albedo[i], ts::ts_material_emission(&sv, &s), e_ss, e_id, visible,
                                 o[i]);
    }
}

void ais_packet(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame, size_t first,
                size_t count, std::vector<float>& out) {
    Packet p;
    std::array<bool, kLanes> hit{};
    std::array<uint32_t, kLanes> px{}, py{};
    for (size_t item = first; item < std::min(count, first + kLanes); ++item) {
        const int i = p.lanes++;
        float* o = &out[item * TS_AIS_ITEM_FLOATS];
        std::fill(o, o + TS_AIS_ITEM_FLOATS, 0.0f);
        uint32_t k, mask;
        ts::ts_ais_item_decode(&sv, &frame, static_cast<uint32_t>(item), &px[i], &py[i], &k, &mask);
        p.set[i] = k;
        p.mask[i] = mask;
        if (ts::ts_ais_item_has_surface(mask)) hit[i] = view_lane(sv, tracer, frame, p, i, px[i], py[i], k, mask);
    }
    gather_links(sv, tracer, frame, p, false);  // AIS items: pixels scattered over edges
    for (int i = 0; i < p.lanes; ++i) {
        float* o = &out[(first + i) * TS_AIS_ITEM_FLOATS];
        if (hit[i]) {
            ts::float3 e_ss, e_id;
            float visible;
            ts::ts_igi_gather_end(&p.gather[i], &frame, &e_ss, &e_id, &visible);
            ts::ts_ais_item_store_surface(e_ss, e_id, o);
        }
        ts::ts_ais_item_media(&sv, &tracer, &frame, px[i], py[i], p.set[i], p.mask[i], o);
    }
}

}  // namespace

void igi_surface_packets(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame,
                         std::vector<float>& out) {
    const uint32_t blocks = ts::ts_packet_block_count(&frame);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, blocks, 4), [&](const tbb::blocked_range<uint32_t>& r) {
        set_ftz_daz();
        for (uint32_t b = r.begin(); b < r.end(); ++b) surface_block(sv, tracer, frame, b, out);
    });
}

void ais_item_packets(const ts::TsSceneView& sv, const ts::TsTracer& tracer, const TsFrame& frame, size_t count,
                      std::vector<float>& out) {
    const size_t packets = (count + kLanes - 1) / kLanes;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, packets, 4), [&](const tbb::blocked_range<size_t>& r) {
        set_ftz_daz();
        for (size_t q = r.begin(); q < r.end(); ++q) ais_packet(sv, tracer, frame, q * kLanes, count, out);
    });
}

}  // namespace tessera
