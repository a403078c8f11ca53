#include "image/resample.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tessera {
namespace {

// One axis's taps: the two source indices around output index i and the second's weight.
struct Taps {
    int a, b;
    float w;
};

std::vector<Taps> axis_taps(int src, int dst) {
    std::vector<Taps> taps(dst);
    const double ratio = double(src) / dst;
    for (int i = 0; i < dst; ++i) {
        const double x = std::clamp((i + 0.5) * ratio - 0.5, 0.0, double(src - 1));
        const int a = static_cast<int>(x);
        taps[i] = {a, std::min(a + 1, src - 1), static_cast<float>(x - a)};
    }
    return taps;
}

}  // namespace

Image resize_bilinear(const Image& src, int width, int height) {
    if (width < 1 || height < 1 || src.width < 1 || src.height < 1)
        throw std::invalid_argument("resize_bilinear: sizes must be >= 1");
    Image out;
    out.width = width, out.height = height, out.x0 = src.x0, out.y0 = src.y0;
    const std::vector<Taps> tx = axis_taps(src.width, width), ty = axis_taps(src.height, height);
    for (const ImageChannel& c : src.channels) {
        ImageChannel& o = out.channels.emplace_back();
        o.name = c.name;
        o.data.resize(size_t(width) * height);
        for (int y = 0; y < height; ++y) {
            const float* r0 = c.data.data() + size_t(ty[y].a) * src.width;
            const float* r1 = c.data.data() + size_t(ty[y].b) * src.width;
            const float wy = ty[y].w;
            for (int x = 0; x < width; ++x) {
                const Taps& t = tx[x];
                const float v00 = r0[t.a], v01 = r0[t.b], v10 = r1[t.a], v11 = r1[t.b];
                float v = (1 - wy) * ((1 - t.w) * v00 + t.w * v01) + wy * ((1 - t.w) * v10 + t.w * v11);
                if (!std::isfinite(v)) {  // the nearest tap: no inf·0
                    const float* row = wy < 0.5f ? r0 : r1;
                    v = row[t.w < 0.5f ? t.a : t.b];
                }
                o.data[size_t(y) * width + x] = v;
            }
        }
    }
    return out;
}

}  // namespace tessera
