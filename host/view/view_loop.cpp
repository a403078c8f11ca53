#include "view/view_loop.h"

#include <chrono>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "image/atomic_file.h"
#include "render/interrupt.h"
#include "render/sequence.h"

namespace tessera::view {

namespace {
constexpr double kFixedDt = 1.0 / 30.0;  // seconds per frame of scripted and replayed runs
}

ViewLoop::ViewLoop(ViewSession& session, LoopOptions options) : session_(session), options_(std::move(options)) {}

bool ViewLoop::done() const {
    // SIGINT/SIGTERM inside the command's InterruptScope end the run like Esc, after the
    // frame in progress: the frames so far keep their times and images.
    if (session_.quit_requested() || interrupt_signal()) return true;
    if (!options_.path.empty()) return frame_ >= static_cast<int>(options_.path.size());
    if (options_.headless) return options_.script.empty() || frame_ > options_.script.back().frame;
    return false;
}

void ViewLoop::step(double wall_dt) {
    while (next_event_ < options_.script.size() && options_.script[next_event_].frame <= frame_)
        session_.handle(options_.script[next_event_++].event);
    if (session_.quit_requested()) return;
    if (frame_ < static_cast<int>(options_.path.size())) {
        session_.set_camera(options_.path[frame_].camera);
        session_.set_animation_frame(options_.path[frame_].frame);
    }
    const auto t0 = std::chrono::steady_clock::now();
    FrameTime t;
    t.frame = frame_;
    t.report = session_.advance(options_.fixed_dt ? kFixedDt : wall_dt);
    t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    times_.push_back(t);
    if (!options_.record.empty()) recorded_.push_back({session_.camera(), session_.animation_frame()});
    if (!options_.frame_images.empty()) {
        // A window's frames are not known at the start, so each is checked as it comes
        // (a headless run's were checked before the first frame).
        const std::filesystem::path image = frame_output_path(options_.frame_images / "frame.exr", frame_,
                                                                      options_.frame_image_digits);
        if (session_.reserved(image))
            std::fprintf(stderr, "tessera view: frame image %d skipped: %s is a file this run reads or writes\n",
                         frame_, image.c_str());
        else
            write_exr(image, session_.accumulation());
    }
    ++frame_;
}

void ViewLoop::finish(const std::string& scene_name) const {
    if (!options_.record.empty() && !recorded_.empty()) write_camera_path(options_.record, recorded_, scene_name);
    double moving_sum = 0, all_sum = 0;
    int moving = 0;
    nlohmann::json frames = nlohmann::json::array();
    for (const FrameTime& t : times_) {
        all_sum += t.seconds;
        if (t.report.moving) moving_sum += t.seconds, ++moving;
        const StageTimes& s = t.report.stages;
        frames.push_back({{"frame", t.frame},
                          {"ms", 1e3 * t.seconds},
                          {"moving", t.report.moving},
                          {"rendered", t.report.rendered},
                          {"passes", t.report.passes},
                          {"rays", s.rays},
                          {"stages_ms",
                           {{"vpl", 1e3 * s.vpl}, {"surface", 1e3 * s.surface}, {"media", 1e3 * s.media},
                            {"filter", 1e3 * s.filter}, {"ais", 1e3 * s.ais}, {"edges", 1e3 * s.edges},
                            {"cache", 1e3 * s.cache},
                            {"pass", 1e3 * s.total}}}});
        const BudgetReport& b = t.report.budget;
        if (b.applied)
            frames.back()["budget"] = {{"scale", b.scale}, {"width", b.width}, {"height", b.height},
                                       {"tile", b.tile}, {"vpl_paths", b.vpl_paths},
                                       {"shadow_samples", b.shadow_samples}, {"out_of_reach", b.out_of_reach}};
    }
    const double moving_ms = moving ? 1e3 * moving_sum / moving : 0.0;
    // The last frame's error against --reference: the HUD's figure, for a headless run too.
    const double error = session_.reference_error();
    if (!options_.times.empty()) {
        const nlohmann::json j = {{"scene", scene_name},
                                  {"method", method_name(session_.method())},
                                  {"backend", session_.backend_description()},
                                  {"width", session_.width()},
                                  {"height", session_.height()},
                                  {"target_fps", session_.target_fps()},
                                  {"frames", frames},
                                  {"moving_frames", moving},
                                  {"mean_moving_ms", moving_ms},
                                  {"moving_fps", moving_ms > 0 ? 1e3 / moving_ms : 0.0},
                                  {"mean_ms", times_.empty() ? 0.0 : 1e3 * all_sum / times_.size()},
                                  {"relmse_vs_reference", error >= 0 ? nlohmann::json(error) : nlohmann::json(nullptr)}};
        const std::string text = j.dump(1) + "\n";
        write_file_atomic(options_.times, text.data(), text.size());
    }
    const unsigned passes = session_.passes();
    std::string reference;
    if (error >= 0) reference = ", relMSE vs reference " + std::to_string(error);
    char rate[96] = "none moving";  // a view never moved has no moving-frame rate
    if (moving)
        std::snprintf(rate, sizeof rate, "%d moving: %.1f ms per moving frame (%.1f fps)", moving, moving_ms,
                      1e3 / moving_ms);
    std::fprintf(stderr, "tessera view: %zu %s, %s, %u %s at the end%s\n", times_.size(),
                 times_.size() == 1 ? "frame" : "frames", rate, passes, passes == 1 ? "pass" : "passes",
                 reference.c_str());
}

}  // namespace tessera::view
