// The viewer's frame-time budget (--target-fps): picks, for each moving-camera frame, the
// interleave size, VPL paths per set and light samples per pixel, and the render
// resolution (a per-axis scale of the window), so that a frame takes about 1/F seconds
// (docs/viewer.md §4).
//
// Settings come from the accuracy sweep's Pareto front (bench/results/accuracy/<scene>.csv:
// error against time of one pass of each setting). The sweep's times come from another
// machine and image size, so the budget is a feedback controller: it keeps a measured cost
// factor (measured frame time / (the sweep's time of the setting × the fraction of the
// window's pixels rendered)), smoothed over frames, and predicts each choice's time as
// sweep time × cost factor × scale². Resolution comes second: the scale drops below 1 only
// when even the fastest setting misses the budget at full resolution, as Blender's and
// LuxCore's viewports render fewer pixels while the camera moves.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace tessera::view {

/// One setting of an igi-family method and its one-pass cost and error in the sweep.
struct BudgetPoint {
    std::string method;          ///< "igi", "ais" or "ais-max" (or any method: a front of its own settings)
    uint32_t tile = 0, vpl_paths = 0, shadow_samples = 0;  ///< the setting (from the sweep's row)
    double seconds = 0;          ///< median pass time in the sweep
    double relmse = 0;           ///< one pass's relMSE against the reference in the sweep
};

/// Reads the one-pass rows (spp 1) of igi, ais and ais-max of `backend` from an accuracy
/// sweep CSV (bench/accuracy: columns scene, backend, method, setting, spp, ...,
/// median_pass_s, ..., relmse) and returns each method's Pareto front: sorted by time,
/// each point with a lower relMSE than every faster one. Throws InputError naming the file
/// when it cannot be read or lacks the columns.
std::vector<BudgetPoint> read_pareto_front(const std::filesystem::path& csv, const std::string& backend);

/// The Pareto front of `points` (all of one method): sorted by seconds, keeping a point
/// only when its relMSE is below that of every faster point.
std::vector<BudgetPoint> pareto_front(std::vector<BudgetPoint> points);

struct BudgetOptions {
    /// The floor of the per-axis resolution scale, in (0, 1]. 1/8: Blender Cycles starts
    /// its viewport preview at 64 pixels ("Start Pixels", preview_start_resolution, default
    /// 64), 1/8 of a 512-pixel window, and refines from there; we go no lower.
    double min_scale = 0.125;
    /// The cost factor before any frame is measured: the window's pixels / the sweep's
    /// (time grows with pixels); 1 when the sweep's size is unknown.
    double initial_cost = 1.0;
};

class FrameBudget {
public:
    /// `front`: one method's points (pareto_front); must not be empty. `target_seconds` > 0.
    /// Throws std::invalid_argument otherwise, or for a min_scale outside (0, 1] or an
    /// initial_cost that is not a finite number > 0.
    FrameBudget(double target_seconds, std::vector<BudgetPoint> front, BudgetOptions options = {});

    /// The setting for the next moving frame.
    const BudgetPoint& choice() const { return front_[choice_]; }
    /// The per-axis resolution scale of the next moving frame, in [min_scale, 1].
    double scale() const { return scale_; }
    /// Records the measured time of a moving frame rendered with choice() at a fraction
    /// `pixel_fraction` of the window's pixels (about scale()², after rounding to whole
    /// pixels), updates the cost factor (exponential average, weight 0.3 for the new frame)
    /// and chooses the next frame's setting and scale:
    /// - full resolution while any setting is predicted to fit: the lowest-error one, a
    ///   faster one at once when over budget, a slower one only when predicted within 90%
    ///   of the target (hysteresis, so the choice does not flip at a boundary);
    /// - else the fastest setting at the scale predicted to take 98% of the target, kept
    ///   while its prediction stays within 90–108% of the target (a dead band, so the
    ///   image size does not change every frame), and back to full resolution only when
    ///   the fastest setting is predicted within 90% there.
    void observe(double measured_seconds, double pixel_fraction = 1.0);
    /// Measured time / predicted time at the sweep's size (see the file comment).
    double cost_factor() const { return cost_; }
    double target_seconds() const { return target_; }
    double min_scale() const { return min_scale_; }
    /// The predicted time of front point `point` at per-axis scale `scale`.
    double predicted_seconds(size_t point, double scale) const;
    /// True at the cheapest choice there is: the fastest setting at the floor scale.
    bool at_cheapest() const { return choice_ == 0 && scale_ <= min_scale_; }

private:
    double fitting_scale() const;

    double target_;
    std::vector<BudgetPoint> front_;
    double min_scale_;
    size_t choice_ = 0;
    double scale_ = 1.0;
    double cost_ = 1.0;
    bool measured_ = false;
};

}  // namespace tessera::view
