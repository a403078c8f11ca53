// The viewer's frame-time budget (--target-fps): picks the interleave size, VPL paths per
// set and light samples per pixel of the moving-camera frames so that a frame takes about
// 1/F seconds, preferring the settings on the accuracy sweep's Pareto front
// (bench/results/accuracy/<scene>.csv: error against time of one pass of each setting).
// The sweep's times come from another machine and image size, so the budget keeps a
// measured scale factor: measured pass time / the sweep's time for the setting in use,
// smoothed over frames, and predicts each candidate's time as its sweep time × scale.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace tessera::view {

/// One setting of an igi-family method and its one-pass cost and error in the sweep.
struct BudgetPoint {
    std::string method;          ///< "igi", "ais" or "ais-max"
    uint32_t tile = 3, vpl_paths = 32, shadow_samples = 8;
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

class FrameBudget {
public:
    /// `front`: one method's points (pareto_front); must not be empty. `target_seconds` > 0.
    FrameBudget(double target_seconds, std::vector<BudgetPoint> front);

    /// The setting for the next moving frame: the lowest-error point whose predicted time
    /// (seconds × scale) fits the target, else the fastest point.
    const BudgetPoint& choice() const { return front_[choice_]; }
    /// Records the measured time of a moving frame rendered with choice(), updates the
    /// scale (exponential average, weight 0.3 for the new frame) and the choice. A point
    /// faster than the current one is taken at once when the frame was over budget;
    /// a slower one only when it is predicted within 90% of the target (hysteresis, so
    /// the choice does not flip every frame around the boundary).
    void observe(double measured_seconds);
    double scale() const { return scale_; }
    double target_seconds() const { return target_; }

private:
    double target_;
    std::vector<BudgetPoint> front_;
    size_t choice_ = 0;
    double scale_ = 1.0;
    bool measured_ = false;
};

}  // namespace tessera::view
