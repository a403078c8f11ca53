#include "gi/irradiance_cache.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "kernels/shared/ic_gather.h"
#include "kernels/shared/ic_lookup.h"

namespace tessera {

ts::TsSurface ic_record_surface(const IcRecord& r) { return ts::ts_ic_record_surface(r.surface.data()); }

float ic_record_radius(float harmonic_mean, float pixel_size, float min_px, float max_px) {
    const float r = std::clamp(harmonic_mean, min_px * pixel_size, max_px * pixel_size);
    return std::max({r, 1e-6f * pixel_size, std::numeric_limits<float>::min()});
}

void IrradianceCache::rebuild(glm::vec3 lo, glm::vec3 hi) {
    for (const IcRecord& r : records_) {
        lo = glm::min(lo, r.position() - glm::vec3(a_ * r.radius));
        hi = glm::max(hi, r.position() + glm::vec3(a_ * r.radius));
    }
    const glm::vec3 size = hi - lo;
    // 1% margin: a point on the root's far faces still falls inside it.
    const float half = 0.505f * std::max({size.x, size.y, size.z, 1e-6f});
    nodes_.assign(1, Node{0.5f * (lo + hi), half, 0, {}});
    for (uint32_t i = 0; i < records_.size(); ++i) {
        const float r = a_ * records_[i].radius;
        insert_into(0, i, records_[i].position() - glm::vec3(r), records_[i].position() + glm::vec3(r), r, 0);
    }
    dirty_ = true;
}

void IrradianceCache::insert(const IcRecord& rec) {
    if (nodes_.empty()) rebuild(rec.position(), rec.position());
    records_.push_back(rec);
    const float r = a_ * rec.radius;
    insert_into(0, static_cast<uint32_t>(records_.size() - 1), rec.position() - glm::vec3(r),
                rec.position() + glm::vec3(r), r, 0);
    dirty_ = true;
}

// Descends while the children are still at least as large as the sphere (half edge ≥ r),
// into every child the sphere's box meets; stores the record where it stops (shared/ic.h).
void IrradianceCache::insert_into(uint32_t node, uint32_t record, glm::vec3 lo, glm::vec3 hi, float r, int depth) {
    const float child_half = 0.5f * nodes_[node].half;
    if (child_half < r || depth == TS_IC_MAX_DEPTH) {
        nodes_[node].refs.push_back(record);
        return;
    }
    if (nodes_[node].first_child == 0) {
        const auto first = static_cast<uint32_t>(nodes_.size());
        const glm::vec3 c = nodes_[node].centre;
        for (int o = 0; o < 8; ++o) {
            const glm::vec3 s((o & 1) ? 1.0f : -1.0f, (o & 2) ? 1.0f : -1.0f, (o & 4) ? 1.0f : -1.0f);
            nodes_.push_back(Node{c + s * child_half, child_half, 0, {}});
        }
        nodes_[node].first_child = first;
    }
    const uint32_t first = nodes_[node].first_child;
    for (uint32_t o = 0; o < 8; ++o) {
        const Node& ch = nodes_[first + o];
        // The lookup sends x to octant (x >= centre) per axis; a closed test here keeps
        // points on a boundary plane inside the child the lookup picks.
        bool meets = true;
        for (int a = 0; a < 3; ++a)
            meets = meets && lo[a] <= ch.centre[a] + ch.half && hi[a] >= ch.centre[a] - ch.half;
        if (meets) insert_into(first + o, record, lo, hi, r, depth + 1);
    }
}

const IcCacheBuffers& IrradianceCache::buffers() {
    if (!dirty_) return flat_;
    flat_.nodes.assign(std::max<size_t>(1, nodes_.size()) * TS_IC_NODE_FLOATS, 0.0f);
    flat_.refs.clear();
    for (size_t i = 0; i < nodes_.size(); ++i) {
        float* n = &flat_.nodes[i * TS_IC_NODE_FLOATS];
        const Node& src = nodes_[i];
        n[TS_IC_NODE_CENTRE] = src.centre.x, n[TS_IC_NODE_CENTRE + 1] = src.centre.y;
        n[TS_IC_NODE_CENTRE + 2] = src.centre.z, n[TS_IC_NODE_HALF] = src.half;
        const auto first = static_cast<uint32_t>(flat_.refs.size()), count = static_cast<uint32_t>(src.refs.size());
        std::memcpy(&n[TS_IC_NODE_CHILD], &src.first_child, 4);
        std::memcpy(&n[TS_IC_NODE_FIRST], &first, 4);
        std::memcpy(&n[TS_IC_NODE_COUNT], &count, 4);
        flat_.refs.insert(flat_.refs.end(), src.refs.begin(), src.refs.end());
    }
    if (flat_.refs.empty()) flat_.refs.push_back(0);  // device buffers cannot be empty
    flat_.records.assign(std::max<size_t>(1, records_.size()) * TS_IC_RECORD_FLOATS, 0.0f);
    for (size_t i = 0; i < records_.size(); ++i) {
        float* r = &flat_.records[i * TS_IC_RECORD_FLOATS];
        const IcRecord& src = records_[i];
        const float* g = src.surface.data();
        std::copy(g + TS_IC_GBUF_POSITION, g + TS_IC_GBUF_POSITION + 3, r + TS_IC_RECORD_POSITION);
        std::copy(g + TS_IC_GBUF_NORMAL, g + TS_IC_GBUF_NORMAL + 3, r + TS_IC_RECORD_NORMAL);
        std::copy(src.e.begin(), src.e.end(), r + TS_IC_RECORD_E);
        r[TS_IC_RECORD_RADIUS] = src.radius;
    }
    dirty_ = false;
    return flat_;
}

float IrradianceCache::lookup(glm::vec3 x, glm::vec3 n, glm::vec3* e) {
    const IcCacheBuffers& b = buffers();
    ts::float3 out;
    const float w = ts::ts_ic_interpolate(b.nodes.data(), b.refs.data(), b.records.data(), {x.x, x.y, x.z},
                                          {n.x, n.y, n.z}, a_, &out);
    *e = {out.x, out.y, out.z};
    return w;
}

}  // namespace tessera
