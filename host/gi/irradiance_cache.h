// The irradiance cache of instant caching (docs/instant-caching.md §3-6): records, the octree
// over their validity spheres, and its flat form (IcCacheBuffers) that the interpolation
// kernel and the host's coverage test both read through kernels/shared/ic.h.
//
// Concurrency: lookups only read the flat buffers, so any number may run at once (the
// host's coverage test runs them over TBB, the kernels over work-items); insertions are
// made by one thread between lookup phases (a placement level, a dispatch) and the flat
// buffers are re-made before the next phase; a rebuild builds subtrees over TBB, each
// node's records in record order. This keeps placement deterministic: the same G-buffer
// gives the same records on every backend and every run.
#pragma once
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "kernels/shared/geometry.h"
#include "kernels/shared/layout_ic.h"

namespace tessera {

/// An irradiance cache as the interpolation kernel reads it (kernels/shared/ic.h):
/// TS_IC_NODE_FLOATS per octree node (root first), the nodes' record lists
/// concatenated, and TS_IC_RECORD_FLOATS per record.
struct IcCacheBuffers {
    std::vector<float> nodes;
    std::vector<uint32_t> refs;
    std::vector<float> records;
};

/// A record on the host: the surface it was made at, its validity radius and its
/// gathered E = irradiance / π (albedo-free).
struct IcRecord {
    std::array<float, TS_IC_GBUF_FLOATS> surface{};  ///< the G-buffer entry (layout_ic.h)
    float radius = 0.0f;                              ///< R_i, scene units
    float pixel_size = 0.0f;  ///< a pixel's footprint at the record when it was made (radius clamp)
    /// The nearest surface its hemisphere probe found (scene units, capped at the probe's
    /// reach; gi/ic_probe.h): R_i ≤ probe / (2a), so the validity ball stays clear of it.
    float probe = INFINITY;
    /// Seeds its probe rays (kernels/shared/ic_probe.h): a hash of the pixel, pass and seed
    /// it was made at, the same on every backend (its position may differ in the last bit).
    uint32_t probe_key = 0;
    uint32_t last_in_view = 0;  ///< the last frame (InstantCache's count) whose view held it
    uint32_t subset = 0;        ///< the path subset it gathers from (IcSettings::subsets)
    std::array<float, 3> e{};                         ///< irradiance / π, W/m² / π
    glm::vec3 position() const {
        return {surface[TS_IC_GBUF_POSITION], surface[TS_IC_GBUF_POSITION + 1], surface[TS_IC_GBUF_POSITION + 2]};
    }
};

/// The shading code's surface of a record (what shared/vpl.h ts_vpl_geometry reads).
ts::TsSurface ic_record_surface(const IcRecord& r);

/// Ward's validity radius from the harmonic mean distance `harmonic_mean` (scene units; +inf
/// when unknown), clamped to [min_px, max_px] × `pixel_size` (a pixel's footprint at the
/// record, scene units). The clamp (Tabellion & Lamorlette 2004; Křivánek et al. 2006)
/// keeps records from crowding in corners (lower bound) and from smearing detail across
/// the image (upper bound). Never below 1e-6 × pixel_size or FLT_MIN (a camera on the
/// surface would give 0, and a zero radius a NaN weight). Requires min_px <= max_px.
float ic_record_radius(float harmonic_mean, float pixel_size, float min_px, float max_px);

class IrradianceCache {
public:
    /// `error_bound` is Ward's a (> 0): a record covers points within a·R_i.
    explicit IrradianceCache(float error_bound) : a_(error_bound) {}

    float error_bound() const { return a_; }
    const std::vector<IcRecord>& records() const { return records_; }
    /// Mutable access; the flat buffers are re-made before the next lookup.
    std::vector<IcRecord>& records() {
        dirty_ = true;
        return records_;
    }

    /// Re-makes the octree over all records, the root a cube around [lo, hi] and every
    /// record's validity sphere. Call after records were removed or edited in place.
    void rebuild(glm::vec3 lo, glm::vec3 hi);

    /// Adds a record and inserts it in the octree (inside the root given to rebuild()).
    void insert(const IcRecord& r);

    /// The flat buffers (re-made lazily after changes).
    const IcCacheBuffers& buffers();

    /// Σ w_i at (x, n) and the interpolated E, the kernels' lookup run on the host.
    float lookup(glm::vec3 x, glm::vec3 n, glm::vec3* e);

private:
    struct Node {
        glm::vec3 centre;
        float half;
        uint32_t first_child = 0;  // 0: leaf
    };
    // A record stored at a node; a node's records are its refs in the order added (record
    // order), gathered per node when the flat buffers are made.
    struct Ref {
        uint32_t node, record;
    };
    struct Tree {
        std::vector<Node> nodes;
        std::vector<Ref> refs;
    };
    // Stores `record` in the subtree of `node` (at `depth`) of `tree`: the serial build's
    // recursion, also run on one subtree's own tree by the parallel rebuild.
    void insert_record(Tree& tree, uint32_t node, uint32_t record, int depth) const;
    template <class Down>
    void route(Tree& tree, uint32_t node, uint32_t record, int depth, Down&& down) const;

    float a_;
    std::vector<IcRecord> records_;
    Tree tree_;
    IcCacheBuffers flat_;
    bool dirty_ = true;
};

}  // namespace tessera
