// Light paths of instant radiosity (Keller 1997) traced path by path with their
// segments kept: what VPL generation (gi/vpl_generator.h) and the temporal instant cache
// (gi/instant_cache.h) share. A path's Halton point fixes every random decision, so a
// path re-traced in an unchanged scene reproduces its VPLs bit for bit; docs/igi.md §3.
#pragma once
#include <cstdint>
#include <vector>

#include "backend/backend.h"
#include "device/scene_buffers.h"

namespace tessera {

/// One traced ray of a light path: from org along dir (unnormalised is fine) to the hit
/// at parameter t on triangle prim, or escaping (prim = TS_NO_HIT, t = +inf).
struct PathSegment {
    float org[3];
    float dir[3];
    float t;
    uint32_t prim;
};

/// A light path and what it left: VPLs (TS_VPL_FLOATS each, layout_igi.h, in path order) and
/// the segments traced. `light` is the index of the emissive triangle it started on
/// (SceneBuffers::lights order); a path whose start has zero pdf has no segments.
struct LightPath {
    uint64_t index = 0;   ///< Halton point
    uint32_t set = 0;     ///< interleave set its VPLs belong to
    uint32_t light = 0;
    /// Multiplies the flux of every VPL the path leaves: 1/p of a path kept for the view
    /// with probability p (select_paths, gi/path_selection.h), 1 otherwise.
    float weight = 1.0f;
    std::vector<float> vpls;
    /// Ray lights (TS_VRL_FLOATS each, layout_igi.h, in path order), with
    /// LightPathSettings::ray_lights: one per segment that crosses the medium.
    std::vector<float> vrls;
    std::vector<PathSegment> segments;
};

/// `path` to be traced again (trace_light_paths): its index, set and weight, nothing it
/// left. A re-traced path in an unchanged scene leaves the same VPLs bit for bit.
inline LightPath untraced(const LightPath& path) {
    LightPath p;
    p.index = path.index, p.set = path.set, p.weight = path.weight;
    return p;
}

/// The light paths' default cap on segments (surface hits and medium scattering events)
/// per path (IgiSettings::light_path_depth, `--light-path-depth`). Paths end by Russian
/// roulette; the cap only bounds the work. IGI's customary 5 would drop the light of 6+
/// bounces (about ρ⁵ of the indirect light, a few percent in a white room) and make IGI
/// converge to something other than the path-traced reference. A medium that scatters
/// without absorbing ends no path by roulette: light random-walks ~(extent / mean free
/// path)² events: a cap of 64 held 34 of 256 paths in a unit box with σs 30, 512 none,
/// and left the Cornell box filled with σs 30 (16 mean free paths across) ~20% below
/// `pt`, 1,024 within noise of it (docs/igi.md §3).
constexpr uint32_t kLightPathDepth = 1024;

/// Bounces whose surface vertices take Halton dimensions (5 + 3·bounce ..); deeper ones
/// draw from the counter-based generator (ts_light_path_segment): the table grows with
/// the square of its dimensions (a shuffle per prime base), ~100k digits at 64.
constexpr uint32_t kHaltonLightPathBounces = 64;

struct LightPathSettings {
    uint32_t max_bounces = kLightPathDepth;  ///< segments per path (kLightPathDepth)
    uint32_t halton_seed = 0x7e55e7a;  ///< the digit scrambling, fixed for the project
    /// The render's --seed: the scrambling used is halton_seed ^ light_path_seed_mix(seed),
    /// so each seed draws its own light paths (docs/igi.md §3).
    uint32_t seed = 1;
    float inv_paths = 1.0f;            ///< 1 / (paths per set): each VPL's weight carries it
    /// Paths scatter in the scene's medium and leave medium VPLs there (multiple
    /// scattering, ts_light_path_medium); false: segments only attenuate (single scattering).
    bool medium_scattering = false;
    /// With medium_scattering: also a virtual ray light for every segment's stretch inside
    /// the medium (LightPath::vrls; Novák et al. 2012), of flux the path's throughput
    /// entering it: what the ray march gathers by default (IgiSettings::ray_lights) instead of the medium
    /// VPLs, which surfaces still gather (docs/igi.md §6).
    bool ray_lights = false;
    /// Record each path's segments (LightPath::segments: what the temporal cache re-tests).
    /// false lets a backend that traces light paths in a kernel
    /// (Backend::traces_light_paths_in_kernel) do so; the VPLs are the same either way, up
    /// to the last place of a GPU's sin, cos and exp.
    bool segments = true;
};

/// What a render's --seed changes in the light paths' Halton scrambling and the VPL
/// selection's keep decisions: a hash of the seed, 0 for the default seed 1, so that every
/// seed gives independent VPL sets while seed 1 keeps the sequence the project's figures
/// were measured with.
uint32_t light_path_seed_mix(uint32_t seed);

/// Traces `paths` (index and set filled in; vpls, segments and light are overwritten),
/// all bounces of all paths batched through Backend::trace_closest. Returns the number
/// of rays traced.
/// Emission and scattering are kernels/shared/light_path.h (one material switch with the
/// camera paths). Estimator (pbrt-v2 IGI convention, docs/igi.md §3): a path starts at a light
/// picked in proportion to power, at a uniform point y0 (area pdf p_A including the
/// selection) in a cosine-distributed direction, with weight α = Le·π / p_A. At a
/// diffuse hit y with albedo ρ it leaves a VPL of weight C = α·ρ/π · inv_paths, then
/// continues with probability q = min(1, luminance(ρ)) in a cosine direction, α ← α·ρ/q.
/// Mirrors reflect (α ← α·Ks); dielectrics reflect or refract by Fresnel; neither stores
/// a VPL. With a medium every segment attenuates α by its transmittance (the
/// single-scattering model of shared/igi_media.h), or with settings.medium_scattering samples a
/// free-flight distance and may scatter in the medium, leaving a medium VPL (layout_igi.h). Halton dimensions: 0 light, 1-2 point,
/// 3-4 direction, then per bounce 2 for the direction and 1 for roulette/Fresnel.
/// Without settings.segments, on a backend whose traces_light_paths_in_kernel() is true,
/// the paths go to trace_light_paths_in_kernel instead.
uint64_t trace_light_paths(Backend& backend, const SceneBuffers& scene, const LightPathSettings& settings,
                           std::vector<LightPath>& paths);

/// The same paths traced by KernelId::LightPaths (kernels/shared/light_path_trace.h) on
/// any backend: one work item per path through all its segments, the same per-segment
/// code as trace_light_paths, so the same VPLs and ray lights (bit for bit where the
/// device rounds as the host does; rays traced alike). Records no segments. A path that
/// overflows the kernel's slots (layout_light_path.h) is traced again as
/// trace_light_paths does. Returns the number of rays of the paths kept.
uint64_t trace_light_paths_in_kernel(Backend& backend, const SceneBuffers& scene, const LightPathSettings& settings,
                                     std::vector<LightPath>& paths);

}  // namespace tessera
