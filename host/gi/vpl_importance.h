// VPLs that serve the view: candidate VPLs kept or dropped by their contribution to the
// surfaces the camera sees, after Georgiev and Slusallek 2010 ("Simple and robust
// iterative importance sampling of virtual point lights", Eurographics short papers),
// docs/igi.md §3b. Host code shared by every backend: the view points are traced
// through Backend::trace_closest, so all backends keep the same VPLs.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "backend/backend.h"
#include "device/scene_buffers.h"
#include "gi/light_paths.h"
#include "kernels/shared/frame.h"
#include "kernels/shared/layout_igi.h"

namespace tessera {

/// Surfaces seen through a grid of camera rays: 3 floats each of position, shading
/// normal and geometric normal (flipped toward the camera), scene units; for the view
/// rays (ViewVisibility), 3 floats of the point rays leave from (TsSurface::origin,
/// pulled inside its triangle) and 1 of its offset scale (TsSurface::pos_scale). Points
/// made by hand may leave those two empty: the position and its largest coordinate
/// magnitude stand in.
struct ViewPoints {
    std::vector<float> position, normal, geo_normal, origin, pos_scale;
    size_t count() const { return position.size() / 3; }
};

/// The first surfaces of grid × grid camera rays of `frame`'s camera, one through each
/// cell of a grid over the image at a fixed offset in the cell (the same points for the
/// same view, so the VPLs change only when the view or scene does). Rays that escape or
/// first meet a mirror or dielectric leave no point.
ViewPoints trace_view_points(Backend& backend, const SceneBuffers& scene, const TsFrame& frame, uint32_t grid);

/// The view points of a viewer's successive frames, with hysteresis (docs/igi.md §3b).
/// While the camera moves, points traced for an earlier camera are kept until the camera
/// has moved more than kMove of their mean distance or turned more than kTurnDegrees from
/// where they were traced: the VPL selection, a function of the points, then stays the same
/// over several frames instead of changing a little every frame, and the flicker a changed
/// selection brings is paid once per few frames (its frame-to-frame noise adds in
/// quadrature, so k frames of drift in one step cost √k of one frame's, not k). A frame
/// whose camera is the previous frame's (at rest: the passes of an accumulation) gets points
/// traced afresh, the same as trace_view_points gives `render`, so an accumulation at rest
/// equals `render --spp N`. Stale points change only which VPLs are kept, never the
/// estimate's expectation (a kept VPL carries 1/p whatever p was chosen from).
class ViewPointHistory {
public:
    /// Translation, as a fraction of the points' mean distance from the camera, and turn of
    /// the view direction or up vector, past which moving frames trace new points. The
    /// fly-throughs of bench/flicker move 2% of the look distance and turn 1° a frame, so
    /// these refresh the points every third to fifth frame.
    static constexpr float kMove = 0.05f;
    static constexpr float kTurnDegrees = 3.0f;

    /// The view points for `frame` (trace_view_points with `grid`), kept or traced as above.
    const ViewPoints& points_for(Backend& backend, const SceneBuffers& scene, const TsFrame& frame, uint32_t grid);
    /// Whether a points_for call since clear_kept() kept earlier points.
    bool kept() const { return kept_; }
    void clear_kept() { kept_ = false; }

private:
    using CameraFloats = std::array<float, 12>;
    static CameraFloats camera_of(const TsFrame& frame);
    bool near_traced(const CameraFloats& camera) const;

    ViewPoints points_;
    CameraFloats traced_camera_{}, last_camera_{};
    float mean_distance_ = 0.0f;  // of the points from traced_camera_'s position
    uint32_t grid_ = 0;
    bool have_points_ = false, have_last_ = false, kept_ = false;
};

/// The shadow rays of vpl_view_importance's visibility estimate: `rays` S per surface
/// VPL, traced by `backend`; the draws are keyed by `seed_mix` and the VPL's index, so the
/// same candidates get the same importance. `traced` counts the rays traced.
struct ViewVisibility {
    Backend* backend = nullptr;
    uint32_t rays = 0;
    uint32_t seed_mix = 0;
    uint64_t traced = 0;
};

/// Each VPL's importance for the view, one float per VPL of `vpls` (TS_VPL_FLOATS each):
/// its share of the irradiance at each view point, Φ_i = Σ_j c_ij / E_j, with
/// c_ij = luminance(C_i) · G'_ij (ts_vpl_geometry_term, clamped to `g_clamp` in scene
/// units^-2; visibility is not tested) and E_j = Σ_i c_ij the candidates' own estimate at
/// point j, floored at a thousandth of the points' mean so that a point that sees almost
/// nothing does not claim the whole budget. The Φ_i of points that see something sum to
/// 1 each.
/// Why shares and no visibility: each view point counts alike whatever its brightness, so
/// the measure follows relative error, as the eye does, where Georgiev and Slusallek
/// weigh by absolute image contribution; and with shadow rays, measured on the Cornell
/// box and Sibenik, the frames were no better at 1.6-2× the frame time (docs/igi.md §3b).
/// Medium VPLs get 0: their value lies in the medium, which the points do not see.
/// `e_vpls`: E_j sums over the first e_vpls VPLs only (all by default). E_j only weighs
/// the points, so any estimate of it keeps the selection unbiased; the instant cache's M
/// path subsets take it from the first subset's candidates, at 1/M of the sum's cost
/// (docs/instant-caching.md §2).
///
/// `visibility` (with rays S > 0): each surface VPL's Φ_i times the fraction of S shadow
/// rays that reach it from view points drawn in proportion to its terms c_ij·w_j
/// (stratified over their cumulative sum), an unbiased estimate of Σ_j c_ij w_j V_ij:
/// a VPL behind a wall from every point it would light gets 0 (kept only by the
/// selection's floor). The instant cache's paths are chosen so (docs/instant-caching.md §2).
///
/// `where` (optional): each VPL's mean view point position weighed by its terms c_ij·w_j
/// (before visibility), 3 floats a VPL in VPL order, scene units; NaN for medium VPLs and
/// VPLs whose terms are all 0 (a VPL whose view rays are all blocked keeps its place, with
/// importance 0): where in the view the VPL's light lands, select_paths' sort key
/// (gi/path_selection.h). In float, as a key only.
std::vector<float> vpl_view_importance(const ViewPoints& points, const std::vector<float>& vpls, float g_clamp,
                                       size_t e_vpls = SIZE_MAX, ViewVisibility* visibility = nullptr,
                                       std::vector<float>* where = nullptr);

/// The same importance from KernelId::VplImportancePoints and VplImportanceVpls
/// (kernels/shared/vpl_importance.h): the terms and sums of vpl_view_importance where the
/// kernels run, the host forming only the points' weights; the same floats bit for bit
/// where the device rounds as the host does and has doubles. `e_chunk` > 0 sums E_j in
/// parts of e_chunk VPLs, one work item a point and part (np × ⌈nv / e_chunk⌉ items, not
/// np), whose results the host reads back and adds in order; 0 (or ≥ the VPL count): one
/// item a point. The parts change no bit of Φ in practice: E_j is a double sum of float
/// terms, exact in any order while it fits a double's 53 bits (a float's 24, the count's
/// log2, 11 for 2,000 terms, and the terms' spread: within 2^18 of each other), and past
/// that its order moves E_j's last double bits, far below Φ's float rounding. Sets
/// the backend's Vpls, VplSetStart and VplImportance inputs (the caller sets the frame's
/// VPLs afterwards). Throws std::invalid_argument for e_chunk past TS_VI_MAX_CHUNK.
std::vector<float> vpl_view_importance_in_kernels(Backend& backend, const ViewPoints& points,
                                                  const std::vector<float>& vpls, float g_clamp, size_t e_chunk = 0);

/// vpl_view_importance_in_kernels, in Backend::importance_chunk()'s parts, on a backend
/// that traces the light paths in a kernel (Backend::traces_light_paths_in_kernel: a GPU,
/// whose host would otherwise hold up the VPL stage with the terms), else
/// vpl_view_importance: the whole VPL stage where its light paths are traced.
std::vector<float> vpl_view_importance(Backend& backend, const ViewPoints& points, const std::vector<float>& vpls,
                                       float g_clamp);

/// The keep probabilities of VPLs with importance `importance` (medium[i] marks a medium
/// VPL): p_i = min(1, (Φ_i + ε Φ̄) / τ), Φ̄ the surface VPLs' mean and ε = 1 (no VPL has
/// probability 0, so the estimate stays unbiased, and p ≥ 1/(2K)), τ chosen so that the surface VPLs'
/// Σ p_i = their count / oversampling: on average, the VPL count of 1/oversampling of the
/// paths. Medium VPLs, and all VPLs when no importance is positive: 1/oversampling.
std::vector<double> keep_probabilities(const std::vector<float>& importance, const std::vector<bool>& medium,
                                       uint32_t oversampling);

/// Keeps each VPL i of [begin, end) of `vpls` with its keep_probabilities p_i and divides
/// a kept VPL's flux by p_i. The decision is the counter-based generator keyed by the
/// VPL's path index and its place in the path, so the same candidates keep the same VPLs;
/// `seed_mix` (light_path_seed_mix of the render's seed) gives each seed its own decisions.
/// Appends the kept VPLs to `out` and returns their count.
uint32_t select_vpls(const std::vector<float>& vpls, const std::vector<float>& importance, size_t begin, size_t end,
                     uint32_t oversampling, uint32_t seed_mix, std::vector<float>& out);

/// The keep probabilities of light paths with importance `importance` (the sum of their
/// VPLs' Φ_i) and `vpls` VPLs each, for a budget in VPLs: p_j = min(1, (Φ_j + ε Φ̄ m_j)/τ),
/// m_j the path's VPL count, Φ̄ the mean Φ per VPL and ε = 1, τ chosen so that
/// Σ p_j m_j = Σ m_j / oversampling. The budget is in VPLs because a record's gather
/// costs one shadow ray a VPL: a budget of paths keeps as many paths but favours the long
/// ones, and cost 1.5× the VPLs on the Cornell box (K = 4). The path's whole importance
/// (not its mean per VPL) decides, because in a room lit through a doorway the VPLs that
/// matter are the late ones of long paths: measured on tests/data/two-rooms, 16 spp, 30
/// seeds, the spread of the image mean was 1.38% with the sum and 1.52% with the mean
/// (2.42% without selection). Paths without VPLs, and all paths when no importance is
/// positive: 1/oversampling. Rounded up to 1/64 steps as keep_probabilities.
std::vector<double> path_keep_probabilities(const std::vector<float>& importance, const std::vector<uint32_t>& vpls,
                                            uint32_t oversampling);

/// Systematic sampling (Madow 1949; Tillé, *Sampling Algorithms*, 2006, §7.2): unit j,
/// of inclusion probability p[j] in [0, 1], is kept when one of the points u, u + 1,
/// u + 2, ... (u in [0, 1)) falls in its interval [C_{j-1}, C_j) of the cumulative sum
/// C. With u uniform each unit is kept with probability exactly p[j], as independent
/// decisions would keep it, but the number kept is floor(Σp) or ceil(Σp) and any run of
/// consecutive units keeps its share to within one: the selection adds no count noise
/// to the estimate. Returns one flag per unit. Each decision depends on every earlier p:
/// a p that moves by a step moves the decisions after it (select_paths, gi/path_selection.h).
std::vector<bool> systematic_sample(const std::vector<double>& p, double u);

}  // namespace tessera
