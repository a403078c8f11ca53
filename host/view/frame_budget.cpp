#include "view/frame_budget.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "util/error.h"

namespace tessera::view {
namespace {

// Splits one CSV line; fields may be quoted (the setting column: "tile=1,vpl-paths=8,...").
std::vector<std::string> split_csv(const std::string& line) {
    std::vector<std::string> fields(1);
    bool quoted = false;
    for (const char c : line) {
        if (c == '"') quoted = !quoted;
        else if (c == ',' && !quoted) fields.emplace_back();
        else fields.back() += c;
    }
    return fields;
}

// "tile=1,vpl-paths=8,shadow-samples=1" into the point; false when a key is missing.
bool parse_setting(const std::string& setting, BudgetPoint& p) {
    std::map<std::string, uint32_t> kv;
    std::stringstream ss(setting);
    for (std::string item; std::getline(ss, item, ',');) {
        const size_t eq = item.find('=');
        if (eq == std::string::npos) return false;
        kv[item.substr(0, eq)] = static_cast<uint32_t>(std::stoul(item.substr(eq + 1)));
    }
    if (!kv.count("tile") || !kv.count("vpl-paths") || !kv.count("shadow-samples")) return false;
    p.tile = kv["tile"];
    p.vpl_paths = kv["vpl-paths"];
    p.shadow_samples = kv["shadow-samples"];
    return true;
}

}  // namespace

std::vector<BudgetPoint> pareto_front(std::vector<BudgetPoint> points) {
    std::sort(points.begin(), points.end(), [](const BudgetPoint& a, const BudgetPoint& b) {
        return a.seconds != b.seconds ? a.seconds < b.seconds : a.relmse < b.relmse;
    });
    std::vector<BudgetPoint> front;
    for (const BudgetPoint& p : points)
        if (front.empty() || p.relmse < front.back().relmse) front.push_back(p);
    return front;
}

std::vector<BudgetPoint> read_pareto_front(const std::filesystem::path& csv, const std::string& backend) {
    std::ifstream in(csv);
    std::string line;
    if (!in || !std::getline(in, line)) throw InputError("accuracy sweep " + csv.string() + ": cannot read the file");
    const std::vector<std::string> header = split_csv(line);
    auto column = [&](const std::string& name) {
        const auto it = std::find(header.begin(), header.end(), name);
        if (it == header.end()) throw InputError("accuracy sweep " + csv.string() + ": no column '" + name + "'");
        return static_cast<size_t>(it - header.begin());
    };
    const size_t c_backend = column("backend"), c_method = column("method"), c_setting = column("setting"),
                 c_spp = column("spp"), c_time = column("median_pass_s"), c_err = column("relmse");
    std::map<std::string, std::vector<BudgetPoint>> by_method;
    while (std::getline(in, line)) {
        const std::vector<std::string> f = split_csv(line);
        if (f.size() < header.size() || f[c_backend] != backend || f[c_spp] != "1") continue;
        if (f[c_method] != "igi" && f[c_method] != "ais" && f[c_method] != "ais-max") continue;
        BudgetPoint p;
        p.method = f[c_method];
        try {
            if (!parse_setting(f[c_setting], p)) continue;
            p.seconds = std::stod(f[c_time]);
            p.relmse = std::stod(f[c_err]);
        } catch (const std::exception&) {
            throw InputError("accuracy sweep " + csv.string() + ": malformed row: " + line);
        }
        // A time or error that is not a finite positive number would steer the budget to nonsense.
        if (!std::isfinite(p.seconds) || !(p.seconds > 0) || !std::isfinite(p.relmse) || !(p.relmse >= 0))
            throw InputError("accuracy sweep " + csv.string() + ": row with median_pass_s " + f[c_time] + " and relmse " +
                             f[c_err] + " (each must be a finite number, the time > 0): " + line);
        by_method[p.method].push_back(p);
    }
    std::vector<BudgetPoint> all;
    for (auto& [method, points] : by_method)
        for (const BudgetPoint& p : pareto_front(points)) all.push_back(p);
    return all;
}

namespace {
constexpr double kUpWithin = 0.9;     // a slower choice only when predicted within 90% of the target
// A new scale aims at 98% of the target and is kept while predicted within 90-108% of it: a
// dead band wider than a frame's usual noise (a few %), so the image size does not change
// every frame, and narrow enough that the rate stays within 10% of the target.
constexpr double kScaleAim = 0.98;
constexpr double kScaleKeepLow = 0.90, kScaleKeepHigh = 1.08;
}  // namespace

FrameBudget::FrameBudget(double target_seconds, std::vector<BudgetPoint> front, BudgetOptions options)
    : target_(target_seconds), front_(std::move(front)), min_scale_(options.min_scale), cost_(options.initial_cost) {
    if (front_.empty()) throw std::invalid_argument("FrameBudget: empty front");
    if (!(target_ > 0) || !std::isfinite(target_)) throw std::invalid_argument("FrameBudget: target must be > 0");
    if (!(min_scale_ > 0 && min_scale_ <= 1)) throw std::invalid_argument("FrameBudget: min_scale must be in (0, 1]");
    if (!(cost_ > 0) || !std::isfinite(cost_)) throw std::invalid_argument("FrameBudget: initial_cost must be > 0");
    // Before any measurement: the best point the predicted times fit into the target, else
    // the fastest one at the scale that fits.
    bool fits = false;
    for (size_t i = 0; i < front_.size(); ++i)
        if (predicted_seconds(i, 1.0) <= target_) choice_ = i, fits = true;
    if (!fits) scale_ = fitting_scale();
}

double FrameBudget::predicted_seconds(size_t point, double scale) const {
    return front_[point].seconds * cost_ * scale * scale;
}

// The scale at which the fastest setting is predicted to take kScaleAim of the target.
double FrameBudget::fitting_scale() const {
    const double s = std::sqrt(kScaleAim * target_ / std::max(predicted_seconds(0, 1.0), 1e-12));
    return std::clamp(s, min_scale_, 1.0);
}

void FrameBudget::observe(double measured_seconds, double pixel_fraction) {
    const double fraction = std::clamp(pixel_fraction, 1e-6, 1.0);
    const double ratio = measured_seconds / std::max(front_[choice_].seconds * fraction, 1e-12);
    cost_ = measured_ ? 0.7 * cost_ + 0.3 * ratio : ratio;
    measured_ = true;
    const bool over = measured_seconds > target_;
    if (scale_ < 1.0) {  // below full resolution: only the fastest setting is in use
        if (predicted_seconds(0, 1.0) <= kUpWithin * target_) {
            scale_ = 1.0;  // full resolution fits again (with margin); settings from the next frame
            return;
        }
        const double predicted = predicted_seconds(0, scale_);
        if (predicted > kScaleKeepHigh * target_ || predicted < kScaleKeepLow * target_) scale_ = fitting_scale();
        return;
    }
    // Full resolution. The front is sorted by time with falling error: the best fit is the last that fits.
    size_t best = 0;
    bool fits = false;
    for (size_t i = 0; i < front_.size(); ++i)
        if (predicted_seconds(i, 1.0) <= target_) best = i, fits = true;
    if (!fits) {  // even the fastest setting misses: fewer pixels
        choice_ = 0;
        scale_ = fitting_scale();
        return;
    }
    if (best < choice_) {
        if (over || predicted_seconds(choice_, 1.0) > target_) choice_ = best;
    } else if (best > choice_) {
        while (best > choice_ && predicted_seconds(best, 1.0) > kUpWithin * target_) --best;
        choice_ = best;
    }
}

}  // namespace tessera::view
