// ViewSession's heads-up display lines (docs/viewer.md §3). Parts of a line are separated
// by " | ", where the window breaks a line that does not fit.
#include "view/view_session.h"

#include <cstdio>
#include <string>

namespace tessera::view {

std::string ViewSession::backend_description() const { return backend_->description(); }

std::vector<std::string> ViewSession::hud_lines(double fps) const {
    std::vector<std::string> lines;
    char buf[256];
    const double ms = 1e3 * last_.total;
    // The igi family counts its rays; direct and pt trace theirs inside one kernel, so
    // their rate is in camera samples (one a pixel and pass), not a made-up 0 rays.
    const bool counts_rays = igi_family(settings_.method);
    const double per_pass = counts_rays ? double(last_.rays) : double(render_width_) * render_height_;
    const double rate = per_pass > 0 && last_.total > 0 ? per_pass / last_.total * 1e-6 : 0.0;
    const char* unit = counts_rays ? "Mrays/s" : "Msamples/s";
    if (last_rendered_)
        std::snprintf(buf, sizeof buf, "%.1f fps | pass %.1f ms | %.2f %s", fps, ms, rate, unit);
    else  // nothing rendered: the window's rate says nothing about the renderer
        std::snprintf(buf, sizeof buf, "idle (%s) | last pass %.1f ms | %.2f %s",
                      paused_ ? "paused" : "all passes accumulated", ms, rate, unit);
    lines.push_back(buf);
    if (igi_family(settings_.method)) {
        std::snprintf(buf, sizeof buf,
                      "VPLs %.1f | SS+ID %.1f | PM %.1f | filter %.1f | AIS %.1f | edges %.1f | cache %.1f ms",
                      1e3 * last_.vpl, 1e3 * last_.surface, 1e3 * last_.media, 1e3 * last_.filter, 1e3 * last_.ais,
                      1e3 * last_.edges, 1e3 * last_.cache);
        lines.push_back(buf);
    }
    std::snprintf(buf, sizeof buf, "method %s on %s", method_name(settings_.method),
                  options_.backend.kind == BackendKind::OpenCL ? "opencl" : "embree");
    lines.push_back(buf);
    lines.push_back("device: " + backend_->description());
    std::snprintf(buf, sizeof buf, "passes %u/%u%s%s | %dx%d | frame %d", passes(), settings_.spp,
                  paused_ ? " (paused)" : "", playing_ ? " (playing)" : "", width_, height_, anim_frame_);
    lines.push_back(buf);
    const uint32_t c = settings_.igi.components;
    std::string components;  // only the igi family has them (direct and pt: no such line part)
    if (counts_rays)
        components = std::string("components ") + (c & TS_COMPONENT_SS ? "SS " : "") + (c & TS_COMPONENT_ID ? "ID " : "") +
                     (c & TS_COMPONENT_PM ? "PM " : "") + (c & TS_COMPONENT_EDGE ? "edge" : "") + " | ";
    std::snprintf(buf, sizeof buf, "%sAOV %s | exposure %+.1f | speed %.3g/s", components.c_str(), aov_name(aov_),
                  exposure_, speed_);
    lines.push_back(buf);
    if (budget_ && last_budget_.applied) {  // what the last moving frame used
        const BudgetReport& b = last_budget_;
        std::snprintf(buf, sizeof buf, "budget %.3g fps: scale %.2f (%dx%d), tile %u, %u VPL paths, %u light sample%s",
                      options_.target_fps, b.scale, b.width, b.height, b.tile, b.vpl_paths, b.shadow_samples,
                      b.shadow_samples == 1 ? "" : "s");
        lines.push_back(buf);
        if (misses_at_cheapest_ >= 3) {
            std::snprintf(buf, sizeof buf, "budget out of reach: %.1f fps at the cheapest choice", 1.0 / last_budget_.seconds);
            lines.push_back(buf);
        }
    } else if (budget_) {
        std::snprintf(buf, sizeof buf, "budget %.3g fps: applies while the camera moves", options_.target_fps);
        lines.push_back(buf);
    }
    if (reference_) {
        std::snprintf(buf, sizeof buf, "relMSE vs reference %.4g", reference_error());
        lines.push_back(buf);
    }
    return lines;
}

}  // namespace tessera::view
