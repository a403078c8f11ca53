#include "gi/clamp_screen.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "kernels/shared/clamp_screen16.h"

namespace tessera {
namespace {

using ts::float3;

// The host's copies as the shared fill's view (kernels/shared/clamp_screen.h).
ts::TsClampScreenView view_of(const ClampScreenInputs& in) {
    ts::TsClampScreenView v;
    v.depth = in.g->depth.data();
    v.normal = in.g->normal.data();
    v.position = in.g->position.data();
    v.throughput = in.throughput->data() + in.throughput_at;
    v.depth_stride = 1;
    v.normal_stride = v.position_stride = 3;
    v.throughput_stride = in.stride;
    return v;
}

// The gather's records as the planes of kernels/shared/clamp_screen16.h: every field of
// layout_igi.h's record (position, A_q, normal, s_q = L_q · A_q with L = ρ · (E_ss + E_id))
// in a plane per column parity, zero where q is no diffuse surface seen directly and in
// the pads, in `data` (resized; every float is written, none zero-filled first).
ts::TsClampScreenPlanes records(const TsFrame& frame, const ClampScreenInputs& in, std::vector<float>& data) {
    const GeometryBuffer& g = *in.g;
    const int w = g.width, h = g.height;
    const float plane = ts::ts_clamp_screen_pixel_plane(&frame);
    const ts::TsClampScreenView v = view_of(in);
    data.resize(ts::ts_clamp_planes_floats(w, h));
    const ts::TsClampScreenPlanes planes = {data.data(), w, h, ts::ts_clamp_planes_pitch(w)};
    const ts::TsClampScreenPlanes* P = &planes;
    const size_t field = ts::ts_clamp_planes_field(P);
    float* out = data.data();
    tbb::parallel_for(tbb::blocked_range<int>(0, h, 8), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y) {
            for (int k = 0; k < TS_CLAMP_SCREEN_FLOATS; ++k)
                for (int parity = 0; parity < 2; ++parity) {
                    float* row = out + k * field + ts::ts_clamp_planes_at(P, parity, y) - TS_CLAMP_PLANE_PAD;
                    const int columns = (w + 1 - parity) / 2;
                    std::fill(row, row + TS_CLAMP_PLANE_PAD, 0.0f);
                    std::fill(row + TS_CLAMP_PLANE_PAD + columns, row + P->pitch, 0.0f);
                }
            for (int x = 0; x < w; ++x) {
                const size_t p = size_t(y) * w + x;
                float rec[TS_CLAMP_SCREEN_FLOATS] = {};
                if (ts::ts_clamp_screen_seen(&v, p)) {
                    const float3 e = ts::ts_f3_load(&(*in.e_ss)[3 * p]) + ts::ts_f3_load(&(*in.e_id)[3 * p]);
                    ts::ts_clamp_screen_record(&frame, plane, ts::ts_f3_load(&g.position[3 * p]),
                                               ts::ts_f3_load(&g.normal[3 * p]),
                                               ts::ts_f3_load(&(*in.albedo)[p * in.stride + in.albedo_at]), e, rec);
                }
                const size_t at = ts::ts_clamp_planes_at(P, x, y);
                for (int k = 0; k < TS_CLAMP_SCREEN_FLOATS; ++k) out[at + k * field] = rec[k];
            }
        }
    });
    return planes;
}

// Lane i of `lanes` as pixel (x, y) seen directly, gathering; its surface from the G-buffer
// (its record's position and normal) and its window radius.
void set_lane(ts::TsClampScreenLanes& lanes, int i, const TsFrame& frame, float plane, float b,
              const GeometryBuffer& g, size_t p) {
    const float3 pos = ts::ts_f3_load(&g.position[3 * p]);
    for (int a = 0; a < 3; ++a) {
        lanes.p[a][i] = g.position[3 * p + a];
        lanes.n[a][i] = g.normal[3 * p + a];
    }
    lanes.r[i] = ts::ts_clamp_screen_radius(plane, ts::ts_clamp_screen_depth(&frame, pos), b);
    lanes.on[i] = -1;
}

// Lanes all off, each holding a finite stand-in surface (the origin) whose terms are masked.
void clear_lanes(ts::TsClampScreenLanes& lanes) {
    for (int i = 0; i < TS_CLAMP_LANES; ++i) {
        for (int a = 0; a < 3; ++a) lanes.p[a][i] = lanes.n[a][i] = 0.0f;
        lanes.r[i] = 0.0f;
        lanes.on[i] = 0;
    }
}

// Lane i's E_res (irradiance / π) into residual at pixel p.
void store_lane(const ts::TsClampScreenLanes& lanes, int i, std::vector<float>& residual, size_t p) {
    for (int a = 0; a < 3; ++a) residual[3 * p + a] = lanes.sum[a][i] * 0.31830989f; /* 1/π */
}

// The edge pixels of row y (edge[x] = 1: seen directly, and no grid neighbour fills them)
// gather themselves. Lane i of a gather at x0 is pixel x0 + 2i, and a lane's sums do not
// depend on the other lanes (ts_clamp_lanes_gather), so the row's edges of one column
// parity share gathers, up to 16 in 32 columns, as the even grid's pixels do.
void gather_edges(ts::TsClampScreenLanes& lanes, const std::vector<uint8_t>& edge, int y, const TsFrame& frame,
                  float plane, float b, const ts::TsMedium* med, const GeometryBuffer& g,
                  const ts::TsClampScreenPlanes* P, std::vector<float>& residual) {
    const int w = g.width;
    for (int parity = 0; parity < 2; ++parity)
        for (int x0 = parity; x0 < w; x0 += 2 * TS_CLAMP_LANES) {
            int any = 0;
            for (int i = 0; i < TS_CLAMP_LANES && x0 + 2 * i < w; ++i) any |= edge[x0 + 2 * i];
            if (!any) continue;
            clear_lanes(lanes);
            for (int i = 0; i < TS_CLAMP_LANES && x0 + 2 * i < w; ++i)
                if (edge[x0 + 2 * i]) set_lane(lanes, i, frame, plane, b, g, size_t(y) * w + x0 + 2 * i);
            ts::ts_clamp_lanes_gather(&lanes, P, x0, y, b, med);
            for (int i = 0; i < TS_CLAMP_LANES; ++i)
                if (lanes.on[i]) store_lane(lanes, i, residual, size_t(y) * w + x0 + 2 * i);
        }
}

// E_res from the planes into `residual`: the gather at every second pixel in x and y (the
// even grid), 16 pixels of a row at a time, then every other pixel seen directly from its
// grid neighbours (ts_clamp_screen_fill), or at an edge its own gather (gather_edges). The
// grid's pixels are only read while the others are written, so both loops run in parallel.
void gather(const TsFrame& frame, float b, const ts::TsMedium* med, const ClampScreenInputs& in,
            const ts::TsClampScreenPlanes& planes, std::vector<float>& residual) {
    const GeometryBuffer& g = *in.g;
    const int w = g.width, h = g.height;
    const float plane = ts::ts_clamp_screen_pixel_plane(&frame);
    const ts::TsClampScreenView v = view_of(in);
    const ts::TsClampScreenPlanes* P = &planes;
    residual.assign(3 * size_t(w) * h, 0.0f);
    tbb::parallel_for(tbb::blocked_range<int>(0, (h + 1) / 2, 2), [&](const tbb::blocked_range<int>& rows) {
        ts::TsClampScreenLanes lanes;
        for (int y = 2 * rows.begin(); y < 2 * rows.end() && y < h; y += 2)
            for (int x0 = 0; x0 < w; x0 += 2 * TS_CLAMP_LANES) {
                clear_lanes(lanes);
                int any = 0;
                for (int i = 0; i < TS_CLAMP_LANES && x0 + 2 * i < w; ++i) {
                    const size_t p = size_t(y) * w + x0 + 2 * i;
                    if (!ts::ts_clamp_screen_seen(&v, p)) continue;
                    set_lane(lanes, i, frame, plane, b, g, p);
                    any = 1;
                }
                if (!any) continue;
                ts::ts_clamp_lanes_gather(&lanes, P, x0, y, b, med);
                for (int i = 0; i < TS_CLAMP_LANES; ++i)
                    if (lanes.on[i]) store_lane(lanes, i, residual, size_t(y) * w + x0 + 2 * i);
            }
    });
    tbb::parallel_for(tbb::blocked_range<int>(0, h, 4), [&](const tbb::blocked_range<int>& rows) {
        ts::TsClampScreenLanes lanes;
        std::vector<uint8_t> edge(w);
        for (int y = rows.begin(); y < rows.end(); ++y) {
            std::fill(edge.begin(), edge.end(), uint8_t(0));
            for (int x = (y % 2 == 0) ? 1 : 0; x < w; x += (y % 2 == 0) ? 2 : 1) {
                const size_t p = size_t(y) * w + x;
                if (!ts::ts_clamp_screen_seen(&v, p)) continue;
                float3 e;
                if (ts::ts_clamp_screen_fill(&v, x, y, w, h, residual.data(), in.same_surface.normal_cos,
                                             in.same_surface.depth_rel, &e))
                    ts::ts_f3_store(&residual[3 * p], e);
                else
                    edge[x] = 1;
            }
            gather_edges(lanes, edge, y, frame, plane, b, med, g, P, residual);
        }
    });
}

}  // namespace

void clamp_screen_residual(const TsFrame& frame, float b, const ts::TsMedium* med, const ClampScreenInputs& in,
                           std::vector<float>& residual, std::vector<float>& planes) {
    const size_t n = in.g->depth.size();
    if (!(b > 0.0f) || !std::isfinite(b) || in.g->position.size() != 3 * n) {
        residual.assign(3 * n, 0.0f);
        return;
    }
    gather(frame, b, med, in, records(frame, in, planes), residual);
}

}  // namespace tessera
