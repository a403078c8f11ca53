// ViewSession's state machine: set-up, accumulation restarts, method and component
// switches and the per-frame advance with the frame budget (docs/viewer.md §1, §4). Input
// handling, the display and the HUD are in session_input.cpp, session_display.cpp and
// session_hud.cpp; tests/view/view_session_test.cpp tests them together.
#include "view/view_session.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "metrics/image_metrics.h"
#include "render/parameters.h"
#include "render/renderer.h"
#include "render/sequence.h"
#include "util/error.h"
#include "view/camera_control.h"

namespace tessera::view {

ViewSession::ViewSession(const Scene& rest, const ViewOptions& options)
    : rest_(rest), options_(options), settings_(options.settings), exposure_(options.exposure) {
    validate_settings(settings_);
    camera_ = home_camera_ = rest_.camera;
    const ImageSize size = render_image_size(settings_, rest_.camera);
    width_ = size.width, height_ = size.height;
    camera_.width = home_camera_.width = width_;
    camera_.height = home_camera_.height = height_;
    speed_ = start_speed_ = options.speed > 0 ? options.speed : default_speed(rest_);
    anim_frame_ = options.first_frame;
    if (!options.reference.empty()) {
        reference_ = read_exr(options.reference);
        if (reference_->width != width_ || reference_->height != height_)
            throw InputError("--reference " + options.reference.string() + ": " + std::to_string(reference_->width) +
                             "x" + std::to_string(reference_->height) + " pixels, the view is " +
                             std::to_string(width_) + "x" + std::to_string(height_));
        metrics::rgb_for_metrics(*reference_, options.reference);  // checks R, G, B exist and are finite
    }
    resolve_ic_subsets(settings_, width_, height_);  // tic's caches: a render's M at this spp and size
    prepare_sequence(settings_, rest_);  // what the method keeps across frames (tic's cache)
    switch_method(0);  // the budget of the starting method
    build_backend();
}

ViewSession::~ViewSession() {
    integrator_.reset();  // before the backend it renders through
    backend_.reset();
}

// The first call makes the backend; later ones (a new animation frame) give it the new
// scene, keeping the device and its compiled programs (Backend::set_scene).
void ViewSession::build_backend() {
    integrator_.reset();
    scene_ = rest_.animation.animated() ? posed_.at(anim_frame_) : rest_;
    auto buffers = std::make_unique<SceneBuffers>(make_scene_buffers(scene_, buffers_.get()));
    plan_ = plan_effects(scene_);
    give_scene(backend_, options_.backend, *buffers, plan_);
    buffers_ = std::move(buffers);  // the previous frame's buffers go only now
    acc_anim_frame_ = anim_frame_;
    dirty_ = true;
}

RenderSettings ViewSession::pass_settings() const {
    RenderSettings s = settings_;
    if (acc_budgeted_ && budget_) {
        s.igi.tile = budget_->choice().tile;
        s.igi.paths_per_set = budget_->choice().vpl_paths;
        s.shadow_samples = budget_->choice().shadow_samples;
    }
    return s;
}

void ViewSession::restart() {
    integrator_.reset();
    acc_kept_points_ = false;
    const RenderSettings s = pass_settings();
    IntegratorSettings is = integrator_settings(s, width_, height_);  // M resolved at the full size (constructor)
    // The AIS guidance and sets AOVs need the host's schedule and its sums. Where AIS
    // reconstructs on the host anyway they are kept at no cost, so any AOV shows at once;
    // a backend that schedules and resolves on the device (a GPU) keeps the frame there
    // while they are not shown, and cycle_aov restarts the accumulation into or out of them.
    if (method_info(s.method).adaptive && (!backend_->resolves_on_device() || schedule_aov(aov_)))
        is.igi.component_aovs = true;
    // A frame resolved on the device brings back its radiance alone unless the display
    // shows the pass's albedo, normal or depth or screenshots keep them (IgiSettings::
    // pass_aovs; cycle_aov restarts the accumulation into or out of them).
    is.igi.pass_aovs = s.aovs || pass_aov(aov_);
    // One history of view points across restarts: moving frames keep the VPL selection's
    // points while the camera moves a little (docs/viewer.md, temporal stability).
    is.igi.view_history = view_history_;
    integrator_ = make_integrator(*backend_, scene_, *buffers_, is);
    render_width_ = width_, render_height_ = height_;
    if (acc_budgeted_ && budget_) {  // fewer pixels while moving; the same field of view
        render_width_ = std::max(1, static_cast<int>(std::lround(width_ * budget_->scale())));
        render_height_ = std::max(1, static_cast<int>(std::lround(height_ * budget_->scale())));
    }
    frame_ = make_render_frame(camera_, render_width_, render_height_, *buffers_, s);
    acc_ = std::make_unique<Accumulator>(render_width_, render_height_);
    acc_camera_ = camera_;
    dirty_ = false;
}

void ViewSession::set_camera(const Camera& camera) {
    camera_ = camera;
    camera_.width = width_;
    camera_.height = height_;
}

void ViewSession::set_animation_frame(int frame) {
    if (frame < options_.first_frame || frame > options_.last_frame)
        throw InputError("animation frame " + std::to_string(frame) + " is outside the viewer's frames " +
                         std::to_string(options_.first_frame) + ".." + std::to_string(options_.last_frame) +
                         " (--frames)");
    anim_frame_ = frame;
}

void ViewSession::switch_method(int step) {
    if (step != 0) {
        const std::vector<MethodInfo>& methods = method_table();
        const int n = static_cast<int>(methods.size());
        settings_.method = methods[(static_cast<int>(settings_.method) + step % n + n) % n].method;
        settings_.ic_state.reset();
        prepare_sequence(settings_, rest_);
        dirty_ = true;
        if (!aov_available(aov_)) aov_ = Aov::Radiance;
    }
    budget_.reset();
    if (options_.target_fps > 0) {
        const double target = 1.0 / options_.target_fps;
        BudgetOptions bo;
        bo.min_scale = options_.min_scale;
        std::vector<BudgetPoint> front;
        for (const BudgetPoint& p : options_.pareto)
            if (p.method == method_name(settings_.method)) front.push_back(p);
        if (!front.empty()) {
            if (options_.pareto_pixels > 0) bo.initial_cost = double(width_) * height_ / options_.pareto_pixels;
            front = pareto_front(front);
        } else {
            // No sweep rows for the method (ic, tic, pt, direct): its own settings, with the
            // resolution as the only knob; assumed to fit until the first frame is measured.
            BudgetPoint own;
            own.method = method_name(settings_.method);
            own.tile = settings_.igi.tile;
            own.vpl_paths = settings_.igi.paths_per_set;
            own.shadow_samples = settings_.shadow_samples;
            own.seconds = target;
            front = {own};
        }
        budget_ = std::make_unique<FrameBudget>(target, front, bo);
    }
    misses_at_cheapest_ = 0;
}

void ViewSession::toggle_component(uint32_t bit) {
    const uint32_t next = settings_.igi.components ^ bit;
    if ((next & ~TS_COMPONENT_EDGE) == 0) {  // edge samples refine the others' pixels
        std::fprintf(stderr, "tessera view: at least one of SS, ID and PM stays on\n");
        return;
    }
    // Components that compute nothing on this scene (PM alone without a medium): the
    // emitters alone. Render refuses them by the same reason.
    if (const std::string why = plan_.idle_reason(next, EffectPlan::Naming::Key); !why.empty()) {
        std::fprintf(stderr, "tessera view: on this scene %s\n", why.c_str());
        return;
    }
    settings_.igi.components = next;
    dirty_ = true;
}

bool ViewSession::aov_available(Aov aov) const {
    const bool ais = method_info(settings_.method).adaptive;
    switch (aov) {
        case Aov::GuidanceSS: case Aov::GuidanceID: case Aov::SetsSS: case Aov::SetsID: return ais;
        case Aov::GuidancePM: case Aov::SetsPM: return ais && plan_.medium_scatters;
        case Aov::Error: return reference_.has_value();
        default: return true;
    }
}

bool ViewSession::schedule_aov(Aov aov) {
    return aov >= Aov::GuidanceSS && aov <= Aov::SetsPM;
}

bool ViewSession::pass_aov(Aov aov) {
    return aov == Aov::Albedo || aov == Aov::Normal || aov == Aov::Depth;
}

void ViewSession::cycle_aov(int step) {
    const int n = static_cast<int>(Aov::Error) + 1;
    int a = static_cast<int>(aov_);
    do a = (a + step + n) % n;
    while (!aov_available(static_cast<Aov>(a)));
    const Aov next = static_cast<Aov>(a);
    if (backend_->resolves_on_device() && method_info(settings_.method).adaptive &&
        schedule_aov(next) != schedule_aov(aov_))
        dirty_ = true;  // the schedule's sums start (or stop) with the next accumulation
    if (backend_->resolves_on_device() && method_info(settings_.method).igi_family &&
        pass_aov(next) != pass_aov(aov_))
        dirty_ = true;  // the passes' albedo, normal and depth start (or stop) coming back
    aov_ = next;
}

FrameReport ViewSession::advance(double dt) {
    FrameReport report;
    glm::vec3 axes(0.0f);
    // A key pressed and released between two frames (a tap, or a slow frame) still counts
    // as held for this frame.
    auto held = [&](int k) { return held_.count(k) || pressed_.count(k) ? 1.0f : 0.0f; };
    axes.x = held('D') - held('A');
    axes.y = held('E') - held('Q');
    axes.z = held('W') - held('S');
    pressed_.clear();
    if (axes != glm::vec3(0.0f)) camera_ = move_camera(camera_, axes, speed_ * static_cast<float>(dt));
    if (paused_ && acc_) {  // keep the image; changes apply when rendering resumes
        last_rendered_ = false;
        report.passes = acc_->passes();
        report.stages = last_;
        return report;
    }
    if (playing_)
        anim_frame_ = anim_frame_ >= options_.last_frame ? options_.first_frame : anim_frame_ + 1;
    if (anim_frame_ != acc_anim_frame_) build_backend();
    const bool first = !acc_;  // the run's first frame starts the accumulation; it is not a move
    const bool moved = dirty_ || first || camera_differs(camera_, acc_camera_);
    const auto frame_start = std::chrono::steady_clock::now();  // the budget's time: set-up and pass
    if (moved) {
        acc_budgeted_ = budget_ != nullptr;
        restart();
    } else if (acc_budgeted_ || acc_kept_points_) {
        // At rest: start over with the full settings and the camera's own view points, as
        // render has them, so the accumulation equals `render --spp N`.
        acc_budgeted_ = false;
        restart();
    }
    report.moving = moved && !first;
    last_rendered_ = false;
    if (acc_->passes() < settings_.spp) {
        const auto t0 = std::chrono::steady_clock::now();
        frame_.pass = acc_->passes();
        view_history_->clear_kept();
        integrator_->render_pass(frame_, pass_);
        acc_kept_points_ = acc_kept_points_ || view_history_->kept();
        acc_->add(pass_);
        IntegratorStats stats;
        integrator_->report(stats);
        last_ = {};
        last_.vpl = stats.igi.vpl_seconds;
        last_.surface = stats.igi.surface_seconds;
        last_.media = stats.igi.media_seconds;
        last_.filter = stats.igi.filter_seconds;
        last_.ais = stats.igi.ais_seconds;
        last_.edges = stats.igi.edge_seconds;
        last_.cache = stats.igi.cache_seconds;
        last_.rays = stats.igi.vpl_rays + stats.igi.pixel_rays + stats.ic.indirect_rays();
        last_.total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        report.rendered = last_rendered_ = true;
        if (moved && acc_budgeted_)
            observe_budget(std::chrono::duration<double>(std::chrono::steady_clock::now() - frame_start).count(), report);
    }
    report.passes = acc_->passes();
    report.stages = last_;
    take_pending_screenshot();
    return report;
}

// A screenshot asked for (P) is of the accumulation as it is; before the first pass there
// is none (a P on frame 0 crashed the viewer), so it is taken after that pass (advance).
void ViewSession::take_pending_screenshot() {
    if (!screenshot_pending_ || !acc_ || acc_->passes() == 0) return;
    screenshot_pending_ = false;
    std::printf("%s\n", save_screenshot().c_str());
    std::fflush(stdout);
}

// Records a budgeted moving frame's time and choice, and says once when even the cheapest
// choice misses the target (three frames in a row, so one slow frame does not).
void ViewSession::observe_budget(double frame_seconds, FrameReport& report) {
    const BudgetPoint& c = budget_->choice();
    BudgetReport& b = report.budget;
    b.applied = true;
    b.scale = budget_->scale();
    b.width = render_width_, b.height = render_height_;
    b.tile = c.tile, b.vpl_paths = c.vpl_paths, b.shadow_samples = c.shadow_samples;
    const bool cheapest = budget_->at_cheapest();
    b.out_of_reach = cheapest && frame_seconds > budget_->target_seconds();
    b.seconds = frame_seconds;
    misses_at_cheapest_ = b.out_of_reach ? misses_at_cheapest_ + 1 : 0;
    if (misses_at_cheapest_ >= 3 && !reach_reported_) {
        std::fprintf(stderr,
                     "tessera view: --target-fps %g is out of reach: %.1f fps at the cheapest choice (scale %.2f, "
                     "%dx%d, tile %u, %u VPL paths, %u light samples)\n",
                     options_.target_fps, 1.0 / frame_seconds, b.scale, b.width, b.height, b.tile, b.vpl_paths,
                     b.shadow_samples);
        reach_reported_ = true;
    }
    last_budget_ = b;
    budget_->observe(frame_seconds, double(render_width_) * render_height_ / (double(width_) * height_));
}

}  // namespace tessera::view
