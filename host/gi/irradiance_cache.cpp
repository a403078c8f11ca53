#include "gi/irradiance_cache.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "kernels/shared/ic_gather.h"
#include "kernels/shared/ic_lookup.h"

namespace tessera {

ts::TsSurface ic_record_surface(const IcRecord& r) { return ts::ts_ic_record_surface(r.surface.data()); }

float ic_record_radius(float harmonic_mean, float pixel_size, float min_px, float max_px) {
    const float r = std::clamp(harmonic_mean, min_px * pixel_size, max_px * pixel_size);
    return std::max({r, 1e-6f * pixel_size, std::numeric_limits<float>::min()});
}

namespace {

// Octree levels split serially before the subtrees below them are built in parallel: up
// to 8² = 64 subtrees, enough to balance 16 threads over a scene's uneven spread.
constexpr int kSplitDepth = 2;

}  // namespace

// Serially to depth kSplitDepth (every node there with its records, in record order), then
// each subtree in its own node pool over TBB, appended in the frontier's order. Each node
// gets the records of the serial build in the same order, so every lookup sums the same
// records in the same order and gives the same bits; only the nodes' numbering differs.
// Sibenik's tic cache, 45k records on the 2-core guest: 24 ms serially, 8 ms so
// (bench/results/tic_host_work.md).
void IrradianceCache::rebuild(glm::vec3 lo, glm::vec3 hi) {
    for (const IcRecord& r : records_) {
        lo = glm::min(lo, r.position() - glm::vec3(a_ * r.radius));
        hi = glm::max(hi, r.position() + glm::vec3(a_ * r.radius));
    }
    const glm::vec3 size = hi - lo;
    // 1% margin: a point on the root's far faces still falls inside it.
    const float half = 0.505f * std::max({size.x, size.y, size.z, 1e-6f});
    tree_.nodes.assign(1, Node{0.5f * (lo + hi), half, 0});
    tree_.refs.clear();
    dirty_ = true;
    struct Part {
        uint32_t node;
        std::vector<uint32_t> records;
    };
    std::vector<Part> frontier(1, Part{0, {}});
    frontier[0].records.resize(records_.size());
    for (uint32_t i = 0; i < records_.size(); ++i) frontier[0].records[i] = i;
    for (int depth = 0; depth < kSplitDepth; ++depth) {
        std::vector<Part> next;
        for (Part& part : frontier) {
            std::array<std::vector<uint32_t>, 8> below;
            for (const uint32_t i : part.records)
                route(tree_, part.node, i, depth, [&](uint32_t o) { below[o].push_back(i); });
            for (uint32_t o = 0; o < 8; ++o)
                if (!below[o].empty())
                    next.push_back(Part{tree_.nodes[part.node].first_child + o, std::move(below[o])});
        }
        frontier = std::move(next);
    }
    std::vector<Tree> pools(frontier.size());
    tbb::parallel_for(size_t(0), frontier.size(), [&](size_t k) {
        Tree& pool = pools[k];
        pool.nodes.push_back(tree_.nodes[frontier[k].node]);
        for (const uint32_t i : frontier[k].records) insert_record(pool, 0, i, kSplitDepth);
    });
    // Pool k's node j > 0 becomes node base[k] + j - 1; its node 0 is the frontier node.
    std::vector<uint32_t> base(frontier.size() + 1, static_cast<uint32_t>(tree_.nodes.size()));
    std::vector<size_t> ref_base(frontier.size() + 1, tree_.refs.size());
    for (size_t k = 0; k < frontier.size(); ++k) {
        base[k + 1] = base[k] + static_cast<uint32_t>(pools[k].nodes.size() - 1);
        ref_base[k + 1] = ref_base[k] + pools[k].refs.size();
    }
    tree_.nodes.resize(base.back());
    tree_.refs.resize(ref_base.back());
    tbb::parallel_for(size_t(0), frontier.size(), [&](size_t k) {
        auto global = [&](uint32_t j) { return j == 0 ? frontier[k].node : base[k] + j - 1u; };
        Tree& pool = pools[k];
        for (Node& n : pool.nodes)
            if (n.first_child != 0) n.first_child = global(n.first_child);
        tree_.nodes[frontier[k].node] = pool.nodes[0];
        std::copy(pool.nodes.begin() + 1, pool.nodes.end(), tree_.nodes.begin() + base[k]);
        for (size_t j = 0; j < pool.refs.size(); ++j)
            tree_.refs[ref_base[k] + j] = Ref{global(pool.refs[j].node), pool.refs[j].record};
    });
}

void IrradianceCache::insert(const IcRecord& rec) {
    if (tree_.nodes.empty()) rebuild(rec.position(), rec.position());
    records_.push_back(rec);
    insert_record(tree_, 0, static_cast<uint32_t>(records_.size() - 1), 0);
    dirty_ = true;
}

void IrradianceCache::insert_record(Tree& tree, uint32_t node, uint32_t record, int depth) const {
    route(tree, node, record, depth,
          [&](uint32_t o) { insert_record(tree, tree.nodes[node].first_child + o, record, depth + 1); });
}

// One level of the descent: while the children are still at least as large as the
// record's sphere (half edge >= r), `down(o)` for every child o the sphere's box meets
// (the children made on the first descent); else the record is stored here (shared/ic.h).
template <class Down>
void IrradianceCache::route(Tree& tree, uint32_t node, uint32_t record, int depth, Down&& down) const {
    std::vector<Node>& nodes = tree.nodes;
    const float r = a_ * records_[record].radius;
    const float child_half = 0.5f * nodes[node].half;
    if (child_half < r || depth == TS_IC_MAX_DEPTH) {
        tree.refs.push_back(Ref{node, record});
        return;
    }
    if (nodes[node].first_child == 0) {
        const auto first = static_cast<uint32_t>(nodes.size());
        const glm::vec3 c = nodes[node].centre;
        for (int o = 0; o < 8; ++o) {
            const glm::vec3 s((o & 1) ? 1.0f : -1.0f, (o & 2) ? 1.0f : -1.0f, (o & 4) ? 1.0f : -1.0f);
            nodes.push_back(Node{c + s * child_half, child_half, 0});
        }
        nodes[node].first_child = first;
    }
    const glm::vec3 lo = records_[record].position() - glm::vec3(r), hi = records_[record].position() + glm::vec3(r);
    const uint32_t first = nodes[node].first_child;
    // The lookup sends x to octant (x >= centre) per axis; a closed test here keeps points
    // on a boundary plane inside the child the lookup picks. Child o lies on side
    // (o >> a) & 1 of axis a, so the box meets it where it meets that side on all three
    // axes: six tests for the eight children, on the children's own centres (octants 0
    // and 7 hold the low and the high side of every axis).
    const glm::vec3 low = nodes[first].centre, high = nodes[first + 7].centre;
    const float h = nodes[first].half;
    bool side[3][2];
    for (int a = 0; a < 3; ++a) {
        side[a][0] = lo[a] <= low[a] + h && hi[a] >= low[a] - h;
        side[a][1] = lo[a] <= high[a] + h && hi[a] >= high[a] - h;
    }
    for (uint32_t o = 0; o < 8; ++o)
        if (side[0][o & 1] && side[1][(o >> 1) & 1] && side[2][(o >> 2) & 1]) down(o);
}

const IcCacheBuffers& IrradianceCache::buffers() {
    if (!dirty_) return flat_;
    const std::vector<Node>& nodes = tree_.nodes;
    // Each node's records, a stable counting sort of the refs by node: record order kept.
    std::vector<uint32_t> first(nodes.size() + 1, 0u);
    for (const Ref& ref : tree_.refs) ++first[ref.node + 1];
    for (size_t i = 0; i < nodes.size(); ++i) first[i + 1] += first[i];
    flat_.refs.resize(tree_.refs.size());
    {
        std::vector<uint32_t> at(first.begin(), first.end() - 1);
        for (const Ref& ref : tree_.refs) flat_.refs[at[ref.node]++] = ref.record;
    }
    // Nodes with neither records nor children are left out (layout_ic.h): the others keep
    // their order, so a node's children stay consecutive in octant order.
    std::vector<uint32_t> index(nodes.size() + 1, 0u);
    for (size_t i = 0; i < nodes.size(); ++i)
        index[i + 1] = index[i] + uint32_t(i == 0 || nodes[i].first_child != 0 || first[i + 1] > first[i]);
    flat_.nodes.assign(std::max<size_t>(1, index.back()) * TS_IC_NODE_FLOATS, 0.0f);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, nodes.size(), 4096), [&](const tbb::blocked_range<size_t>& range) {
        for (size_t i = range.begin(); i < range.end(); ++i) {
            if (index[i + 1] == index[i]) continue;
            float* n = &flat_.nodes[size_t(index[i]) * TS_IC_NODE_FLOATS];
            const Node& src = nodes[i];
            n[TS_IC_NODE_CENTRE] = src.centre.x, n[TS_IC_NODE_CENTRE + 1] = src.centre.y;
            n[TS_IC_NODE_CENTRE + 2] = src.centre.z, n[TS_IC_NODE_HALF] = src.half;
            const uint32_t count = first[i + 1] - first[i];
            uint32_t child = 0, mask = 0;
            if (src.first_child != 0) {
                for (uint32_t o = 0; o < 8; ++o)
                    if (index[src.first_child + o + 1] > index[src.first_child + o]) mask |= 1u << o;
                if (mask != 0) child = index[src.first_child + std::countr_zero(mask)];  // its first kept child
            }
            std::memcpy(&n[TS_IC_NODE_CHILD], &child, 4);
            std::memcpy(&n[TS_IC_NODE_FIRST], &first[i], 4);
            std::memcpy(&n[TS_IC_NODE_COUNT], &count, 4);
            std::memcpy(&n[TS_IC_NODE_MASK], &mask, 4);
        }
    });
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
