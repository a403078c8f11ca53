// One link against the 16 lanes of a packet in SIMD (embree_lanes.h).
#include "backend/embree_lanes.h"

// After the tracer (embree_lanes.h includes it): the shared code declares tracing calls.
#include "kernels/shared/igi.h"

namespace tessera {
namespace {

// Lane i's surface, with the fields the links do not read set to constants (not
// value-initialised: GCC then clears the struct with a memset and stops vectorising).
ts::TsSurface lane_surface(const LaneState& ls, int i) {
    ts::TsSurface s;
    s.position = ts::make_float3(ls.position[0][i], ls.position[1][i], ls.position[2][i]);
    s.geo_normal = ts::make_float3(ls.geo_normal[0][i], ls.geo_normal[1][i], ls.geo_normal[2][i]);
    s.shading_normal = ts::make_float3(ls.shading_normal[0][i], ls.shading_normal[1][i], ls.shading_normal[2][i]);
    s.origin = ts::make_float3(ls.origin[0][i], ls.origin[1][i], ls.origin[2][i]);
    s.pos_scale = ls.pos_scale[i];
    s.uv = ts::make_float2(0.0f, 0.0f);
    s.material = 0;
    s.front_face = 1;
    s.uv_footprint = 0.0f;
    return s;
}

void set_lane_ray(RTCRay16& __restrict r, int i, const ts::TsRay& ray) {
    r.org_x[i] = ray.org.x;
    r.org_y[i] = ray.org.y;
    r.org_z[i] = ray.org.z;
    r.dir_x[i] = ray.dir.x;
    r.dir_y[i] = ray.dir.y;
    r.dir_z[i] = ray.dir.z;
    r.tnear[i] = ray.tmin;
    r.tfar[i] = ray.tmax;
}

// Lane i's shadow ray back out of the packet (Embree changes only occluded lanes' tfar).
ts::TsRay lane_ray(const RTCRay16& r, int i) {
    ts::TsRay ray;
    ray.org = ts::make_float3(r.org_x[i], r.org_y[i], r.org_z[i]);
    ray.dir = ts::make_float3(r.dir_x[i], r.dir_y[i], r.dir_z[i]);
    ray.tmin = r.tnear[i];
    ray.tmax = r.tfar[i];
    return ray;
}

// x where mask is -1, +0 where it is 0: a select GCC 12 vectorises (it does not for
// `mask ? x : 0.0f` or x · (float)(mask != 0) here). Adding the +0 of a hidden lane to a
// sum >= +0 leaves it unchanged bit for bit, so masked sums equal the sums of the visible
// terms alone (terms are finite: contributions and VPL flux are, and so is G' <= b or,
// with the clamp off, cosθ cosθ' / d² at d > 0).
float masked(float x, int mask) { return ts::as_float(ts::as_int(x) & mask); }

// vpl_links for one VPL kind: the kind test in the shared code is folded away by the
// assumption, so the vector loop computes only that kind's emission factor (the
// Henyey–Greenstein phase for a medium VPL, a cosine otherwise). The restrict
// qualifiers, here and on the callers' parameters, are what let GCC vectorise.
template <bool Medium>
void vpl_links_of_kind(const LaneState& __restrict ls, const float (&__restrict vpl)[TS_VPL_FLOATS], float b,
                       float hg, const int* __restrict in, float* __restrict g, int* __restrict traced,
                       RTCRay16& __restrict r) {
    if (ts::ts_vpl_in_medium(vpl) != Medium) __builtin_unreachable();
    for (int i = 0; i < kLanes; ++i) {
        const ts::TsSurface s = lane_surface(ls, i);
        ts::TsRay sh;
        g[i] = ts::ts_vpl_geometry(&s, vpl, b, hg, &sh);
        set_lane_ray(r, i, sh);
    }
    for (int i = 0; i < kLanes; ++i) traced[i] = (g[i] > 0.0f ? -1 : 0) & in[i];
}

}  // namespace

void lane_set(LaneState& ls, int i, const ts::TsSurface& s) {
    const ts::float3 f[4] = {s.position, s.geo_normal, s.shading_normal, s.origin};
    float(*dst[4])[kLanes] = {ls.position, ls.geo_normal, ls.shading_normal, ls.origin};
    for (int a = 0; a < 4; ++a) {
        dst[a][0][i] = f[a].x;
        dst[a][1][i] = f[a].y;
        dst[a][2][i] = f[a].z;
    }
    ls.pos_scale[i] = s.pos_scale;
    for (int c = 0; c < 3; ++c) ls.ss[c][i] = ls.id[c][i] = 0.0f;
    ls.seen[i] = 0;
}

void light_links(const LaneState& __restrict ls, const ts::TsLightSample& sample, const int (&__restrict in)[kLanes],
                 float (&__restrict c)[3][kLanes], int (&__restrict traced)[kLanes], RTCRay16& __restrict r) {
    const ts::TsLightSample q = sample;  // a local copy: invariant in the loop
    for (int i = 0; i < kLanes; ++i) {
        const ts::TsSurface s = lane_surface(ls, i);
        ts::TsRay sh;
        const ts::float3 ci = ts::ts_light_contribution(&s, q, &sh);
        c[0][i] = ci.x, c[1][i] = ci.y, c[2][i] = ci.z;
        traced[i] = (ts::ts_igi_light_link_traced(ci) ? -1 : 0) & in[i];
        set_lane_ray(r, i, sh);
    }
}

void lane_occlusion(const ts::TsTracer& tracer, RTCRay16& r, const int (&__restrict traced)[kLanes], bool coherent,
                    int (&__restrict visible)[kLanes]) {
    int any = 0;
    for (int i = 0; i < kLanes; ++i) any |= traced[i];
    if (any) {
        RTCIntersectContext ctx = ts::ts_packet_context(coherent);
        rtcOccluded16(traced, tracer.scene, &ctx, &r);
    }
    // Embree sets a blocked lane's tfar to -inf (ts_occluded16); the others keep theirs.
    for (int i = 0; i < kLanes; ++i) visible[i] = traced[i] & (r.tfar[i] < 0.0f ? 0 : -1);
}

void light_gather(LaneState& __restrict ls, const float (&__restrict c)[3][kLanes],
                  const int (&__restrict visible)[kLanes], const ts::TsMedium& med, const RTCRay16& r) {
    if (!med.present) {
        const ts::float3 clear = ts::make_float3(1.0f, 1.0f, 1.0f);  // ts_shadow_transmittance without a medium
        for (int i = 0; i < kLanes; ++i) {
            const int v = visible[i];
            const ts::float3 ci = ts::make_float3(masked(c[0][i], v), masked(c[1][i], v), masked(c[2][i], v));
            const ts::float3 t = ts::ts_igi_light_term(ci, clear);
            ls.ss[0][i] += t.x;
            ls.ss[1][i] += t.y;
            ls.ss[2][i] += t.z;
            ls.seen[i] += static_cast<uint32_t>(v) & 1u;
        }
        return;
    }
    for (int i = 0; i < kLanes; ++i) {
        if (!visible[i]) continue;
        const ts::float3 ci = ts::make_float3(c[0][i], c[1][i], c[2][i]);
        const ts::float3 t = ts::ts_igi_light_term(ci, ts::ts_shadow_transmittance(&med, lane_ray(r, i)));
        ls.ss[0][i] += t.x;
        ls.ss[1][i] += t.y;
        ls.ss[2][i] += t.z;
        ++ls.seen[i];
    }
}

void vpl_links(const LaneState& __restrict ls, const float (&__restrict vpl)[TS_VPL_FLOATS], float b, float hg,
               const int (&__restrict in)[kLanes], float (&__restrict g)[kLanes], int (&__restrict traced)[kLanes],
               RTCRay16& __restrict r) {
    if (ts::ts_vpl_in_medium(vpl))
        vpl_links_of_kind<true>(ls, vpl, b, hg, in, g, traced, r);
    else
        vpl_links_of_kind<false>(ls, vpl, b, hg, in, g, traced, r);
}

void vpl_gather(LaneState& __restrict ls, const float (&__restrict vpl)[TS_VPL_FLOATS],
                const float (&__restrict g)[kLanes], const int (&__restrict visible)[kLanes],
                const ts::TsMedium& med, const RTCRay16& r) {
    if (!med.present) {
        const ts::float3 clear = ts::make_float3(1.0f, 1.0f, 1.0f);  // ts_shadow_transmittance without a medium
        for (int i = 0; i < kLanes; ++i) {
            const ts::float3 t = ts::ts_vpl_gather_term(vpl, clear, masked(g[i], visible[i]));
            ls.id[0][i] += t.x;
            ls.id[1][i] += t.y;
            ls.id[2][i] += t.z;
        }
        return;
    }
    for (int i = 0; i < kLanes; ++i) {
        if (!visible[i]) continue;
        ts::float3 sum = ts::make_float3(ls.id[0][i], ls.id[1][i], ls.id[2][i]);
        ts::ts_vpl_gather_add(&sum, vpl, &med, lane_ray(r, i), g[i]);
        ls.id[0][i] = sum.x, ls.id[1][i] = sum.y, ls.id[2][i] = sum.z;
    }
}

}  // namespace tessera
