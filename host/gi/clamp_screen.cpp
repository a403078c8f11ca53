#include "gi/clamp_screen.h"

#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "kernels/shared/clamp_screen.h"

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

// The gather's records in two arrays (layout_igi.h): `hot`, position and A_q
// (TS_CLAMP_SCREEN_HOT_FLOATS a pixel), which every sample reads, and `cold`, normal and
// s_q = L_q · A_q with L = ρ · (E_ss + E_id) (TS_CLAMP_SCREEN_COLD_FLOATS a pixel), read
// only within the clamp radius. Zero where q is no diffuse surface seen directly.
struct Records {
    std::vector<float> hot, cold;
    ts::TsClampScreenRecords view() const {
        return {hot.data(), cold.data(), TS_CLAMP_SCREEN_HOT_FLOATS, TS_CLAMP_SCREEN_COLD_FLOATS};
    }
};

void records(const TsFrame& frame, const ClampScreenInputs& in, Records& rec) {
    const GeometryBuffer& g = *in.g;
    const size_t n = g.depth.size();
    const float plane = ts::ts_clamp_screen_pixel_plane(&frame);
    const ts::TsClampScreenView v = view_of(in);
    rec.hot.assign(TS_CLAMP_SCREEN_HOT_FLOATS * n, 0.0f);
    rec.cold.assign(TS_CLAMP_SCREEN_COLD_FLOATS * n, 0.0f);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t p = r.begin(); p < r.end(); ++p) {
            if (!ts::ts_clamp_screen_seen(&v, p)) continue;
            const float3 e = ts::ts_f3_load(&(*in.e_ss)[3 * p]) + ts::ts_f3_load(&(*in.e_id)[3 * p]);
            ts::ts_clamp_screen_record(&frame, plane, ts::ts_f3_load(&g.position[3 * p]),
                                       ts::ts_f3_load(&g.normal[3 * p]),
                                       ts::ts_f3_load(&(*in.albedo)[p * in.stride + in.albedo_at]), e,
                                       &rec.hot[TS_CLAMP_SCREEN_HOT_FLOATS * p],
                                       &rec.cold[TS_CLAMP_SCREEN_COLD_FLOATS * p]);
        }
    });
}

// E_res at pixel p = (x, y) from the records.
float3 gather_pixel(const TsFrame& frame, float plane, float b, const ts::TsMedium* med, int w, int h,
                    const ts::TsClampScreenRecords& rec, int x, int y) {
    const size_t p = size_t(y) * w + x;
    const float3 pos = ts::ts_f3_load(rec.hot + TS_CLAMP_SCREEN_HOT_FLOATS * p + TS_CLAMP_SCREEN_POSITION);
    const float r = ts::ts_clamp_screen_radius(plane, ts::ts_clamp_screen_depth(&frame, pos), b);
    return ts::ts_clamp_screen_pixel(
        x, y, w, h, pos, ts::ts_f3_load(rec.cold + TS_CLAMP_SCREEN_COLD_FLOATS * p + TS_CLAMP_SCREEN_NORMAL), r, b,
        med, &rec);
}

// E_res from `rec` into `residual`: the gather at every second pixel in x and y (the even
// grid), then every other pixel seen directly from its grid neighbours
// (ts_clamp_screen_fill), or its own gather at an edge. The grid's pixels are only read
// while the others are written, so both loops run in parallel.
void gather(const TsFrame& frame, float b, const ts::TsMedium* med, const ClampScreenInputs& in,
            const Records& parts, std::vector<float>& residual) {
    const GeometryBuffer& g = *in.g;
    const int w = g.width, h = g.height;
    const float plane = ts::ts_clamp_screen_pixel_plane(&frame);
    const ts::TsClampScreenView v = view_of(in);
    const ts::TsClampScreenRecords rec = parts.view();
    residual.assign(3 * size_t(w) * h, 0.0f);
    tbb::parallel_for(tbb::blocked_range<int>(0, (h + 1) / 2, 2), [&](const tbb::blocked_range<int>& rows) {
        for (int y = 2 * rows.begin(); y < 2 * rows.end() && y < h; y += 2)
            for (int x = 0; x < w; x += 2) {
                const size_t p = size_t(y) * w + x;
                if (!ts::ts_clamp_screen_seen(&v, p)) continue;
                ts::ts_f3_store(&residual[3 * p], gather_pixel(frame, plane, b, med, w, h, rec, x, y));
            }
    });
    tbb::parallel_for(tbb::blocked_range<int>(0, h, 4), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y)
            for (int x = (y % 2 == 0) ? 1 : 0; x < w; x += (y % 2 == 0) ? 2 : 1) {
                const size_t p = size_t(y) * w + x;
                if (!ts::ts_clamp_screen_seen(&v, p)) continue;
                float3 e;
                if (!ts::ts_clamp_screen_fill(&v, x, y, w, h, residual.data(), in.same_surface.normal_cos,
                                              in.same_surface.depth_rel, &e))
                    e = gather_pixel(frame, plane, b, med, w, h, rec, x, y);
                ts::ts_f3_store(&residual[3 * p], e);
            }
    });
}

}  // namespace

void clamp_screen_residual(const TsFrame& frame, float b, const ts::TsMedium* med, const ClampScreenInputs& in,
                           std::vector<float>& residual) {
    const size_t n = in.g->depth.size();
    if (!(b > 0.0f) || !std::isfinite(b) || in.g->position.size() != 3 * n) {
        residual.assign(3 * n, 0.0f);
        return;
    }
    Records rec;
    records(frame, in, rec);
    gather(frame, b, med, in, rec, residual);
}

}  // namespace tessera
