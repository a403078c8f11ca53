#include "view/view_session.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "image/atomic_file.h"
#include "image/resample.h"
#include "metrics/image_metrics.h"
#include "render/parameters.h"
#include "render/sequence.h"
#include "util/error.h"
#include "view/camera_control.h"

namespace tessera::view {
namespace {

constexpr float kTurnPerPixel = 0.004f;   // radians of yaw/pitch per pixel dragged
constexpr float kSpeedStep = 1.25f;       // speed factor per scroll notch
constexpr float kMaxScrollNotches = 100;  // 1.25^100 = 5e9 either way of the start speed
constexpr float kExposureStep = 0.5f;     // stops per [ or ] press

// Display transfer: the PNG preview's (clamp, sRGB OETF) from a table, one entry per
// 1/16384 of the unit range: a pow per channel would cost ~10 ms a frame at 512².
struct SrgbTable {
    std::array<uint8_t, 16385> code;
    SrgbTable() {
        for (size_t i = 0; i < code.size(); ++i)
            code[i] = static_cast<uint8_t>(std::lround(255.0 * metrics::tone_map_srgb(double(i) / 16384.0)));
    }
    uint8_t operator()(double v) const {
        if (!(v > 0.0)) return 0;
        if (v >= 1.0) return 255;
        return code[static_cast<size_t>(v * 16384.0 + 0.5)];
    }
};
const SrgbTable& srgb() {
    static const SrgbTable table;
    return table;
}

}  // namespace

const char* aov_name(Aov aov) {
    static const char* names[] = {"radiance", "albedo",      "normal",  "depth",   "guidance.SS", "guidance.ID",
                                  "guidance.PM", "sets.SS", "sets.ID", "sets.PM", "error"};
    return names[static_cast<int>(aov)];
}

ViewSession::ViewSession(const Scene& rest, const ViewOptions& options)
    : rest_(rest), options_(options), settings_(options.settings), exposure_(options.exposure) {
    validate_settings(settings_);
    camera_ = home_camera_ = rest_.camera;
    width_ = settings_.width > 0 ? settings_.width : rest_.camera.width;
    height_ = settings_.height > 0 ? settings_.height : rest_.camera.height;
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
    scene_ = rest_.animation.animated() ? scene_at_frame(rest_, anim_frame_) : rest_;
    auto buffers = std::make_unique<SceneBuffers>(make_scene_buffers(scene_));
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
    const RenderSettings s = pass_settings();
    IntegratorSettings is = integrator_settings(s);
    // The AIS guidance and sets AOVs can be shown at any time: keep their sums (AIS
    // reconstructs on the host anyway, so this costs no read-back).
    if (method_info(s.method).adaptive) is.igi.component_aovs = true;
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
    settings_.igi.components = next;
    dirty_ = true;
}

bool ViewSession::aov_available(Aov aov) const {
    const bool ais = method_info(settings_.method).adaptive;
    switch (aov) {
        case Aov::GuidanceSS: case Aov::GuidanceID: case Aov::SetsSS: case Aov::SetsID: return ais;
        case Aov::GuidancePM: case Aov::SetsPM: return ais && plan_.medium;
        case Aov::Error: return reference_.has_value();
        default: return true;
    }
}

void ViewSession::cycle_aov(int step) {
    const int n = static_cast<int>(Aov::Error) + 1;
    int a = static_cast<int>(aov_);
    do a = (a + step + n) % n;
    while (!aov_available(static_cast<Aov>(a)));
    aov_ = static_cast<Aov>(a);
}

void ViewSession::handle(const InputEvent& e) {
    using K = InputEvent::Kind;
    switch (e.kind) {
        case K::Quit: quit_ = true; return;
        case K::Release: held_.erase(e.key); return;
        case K::Drag: camera_ = turn_camera(camera_, -e.dx * kTurnPerPixel, -e.dy * kTurnPerPixel); return;
        case K::Scroll: {
            // Scene-relative bounds: at most kMaxScrollNotches notches from the start speed
            // either way, so a long scroll cannot reach 0 or overflow a float.
            const float bound = std::pow(kSpeedStep, kMaxScrollNotches);
            speed_ = std::clamp(speed_ * std::pow(kSpeedStep, e.dy), start_speed_ / bound, start_speed_ * bound);
            return;
        }
        case K::Press: break;
    }
    held_.insert(e.key);
    pressed_.insert(e.key);
    switch (e.key) {
        case 'R': camera_ = home_camera_; break;
        case 'C': std::printf("%s\n", camera_json(camera_).c_str()), std::fflush(stdout); break;
        case 'P': std::printf("%s\n", save_screenshot().c_str()), std::fflush(stdout); break;
        case 'M': switch_method(1); break;
        case 'N': switch_method(-1); break;
        case '1': toggle_component(TS_COMPONENT_SS); break;
        case '2': toggle_component(TS_COMPONENT_ID); break;
        case '3': toggle_component(TS_COMPONENT_PM); break;
        case '4': toggle_component(TS_COMPONENT_EDGE); break;
        case 'V': cycle_aov(1); break;
        case 'B': cycle_aov(-1); break;
        case '[': exposure_ -= kExposureStep; break;
        case ']': exposure_ += kExposureStep; break;
        case ' ': paused_ = !paused_; break;
        case 'T': playing_ = !playing_ && options_.last_frame > options_.first_frame; break;
        case 'H': hud_visible_ = !hud_visible_; break;
        case kKeyEscape: quit_ = true; break;
        default: break;
    }
}

std::vector<std::string> ViewSession::key_help() {
    return {"W/A/S/D, Q/E: move; drag: look; scroll: speed; R: reset camera; C: print camera JSON",
            "M/N: next/previous method; 1/2/3/4: toggle SS/ID/PM/edge; V/B: next/previous AOV; [ ]: exposure",
            "Space: pause; T: play animation (--frames); P: screenshot (EXR + PNG); H: HUD; Esc: quit"};
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
    const bool moved = dirty_ || !acc_ || camera_differs(camera_, acc_camera_);
    const auto frame_start = std::chrono::steady_clock::now();  // the budget's time: set-up and pass
    if (moved) {
        acc_budgeted_ = budget_ != nullptr;
        restart();
    } else if (acc_budgeted_) {
        acc_budgeted_ = false;  // at rest: start over with the full settings, as render has them
        restart();
    }
    report.moving = moved;
    last_rendered_ = false;
    if (acc_->passes() < settings_.spp) {
        const auto t0 = std::chrono::steady_clock::now();
        frame_.pass = acc_->passes();
        integrator_->render_pass(frame_, pass_);
        acc_->add(pass_);
        IntegratorStats stats;
        integrator_->report(stats);
        last_ = {};
        last_.vpl = stats.igi.vpl_seconds;
        last_.surface = stats.igi.surface_seconds;
        last_.media = stats.igi.media_seconds;
        last_.filter = stats.igi.filter_seconds;
        last_.ais = stats.igi.ais_seconds;
        last_.cache = stats.igi.cache_seconds;
        last_.rays = stats.igi.vpl_rays + stats.igi.pixel_rays + stats.ic.indirect_rays();
        last_.total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        report.rendered = last_rendered_ = true;
        if (moved && acc_budgeted_)
            observe_budget(std::chrono::duration<double>(std::chrono::steady_clock::now() - frame_start).count(), report);
    }
    report.passes = acc_->passes();
    report.stages = last_;
    return report;
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

// An image of the accumulation's size at the window's: bilinear when the budget rendered
// fewer pixels (docs/viewer.md §4 says why not a G-buffer-guided filter).
Image ViewSession::to_window(Image image) const {
    if (image.width == width_ && image.height == height_) return image;
    return resize_bilinear(image, width_, height_);
}

Image ViewSession::accumulation() const {
    Image image = acc_->mean_image(settings_.aovs, true);
    if (settings_.aovs) integrator_->add_aov_channels(image, acc_->passes());
    return to_window(std::move(image));
}

std::filesystem::path ViewSession::save_screenshot() {
    const std::filesystem::path exr = frame_output_path(options_.screenshot, screenshots_);
    std::filesystem::path png = exr;
    png.replace_extension(".png");
    const Image image = accumulation();
    CommitGroup outputs;  // both files or neither, like render
    write_exr(outputs.add(exr), image);
    write_png(outputs.add(png), image, exposure_);
    outputs.commit();
    ++screenshots_;
    std::fprintf(stderr, "tessera view: screenshot of %u passes: %s\n", acc_->passes(), exr.c_str());
    return exr;
}

Image ViewSession::aov_image() const {
    Image image = acc_->mean_image(true, false);
    integrator_->add_aov_channels(image, std::max(acc_->passes(), 1u));
    return to_window(std::move(image));
}

double ViewSession::reference_error() const {
    if (!reference_ || !acc_ || acc_->passes() == 0) return -1.0;
    const Image image = to_window(acc_->mean_image(false, false));
    return metrics::rel_mse(metrics::rgb_for_metrics(*reference_, options_.reference),
                            metrics::rgb_for_metrics(image, "the view"));
}

void ViewSession::display(std::vector<uint8_t>& rgba) const {
    const size_t n = size_t(width_) * height_;
    rgba.assign(n * 4, 255);
    if (!acc_ || acc_->passes() == 0) return;
    const double scale = std::exp2(double(exposure_));
    const SrgbTable& tm = srgb();
    if (aov_ == Aov::Radiance && acc_->width() != width_) {  // a budgeted moving frame: upsampled
        const Image image = to_window(acc_->mean_image(false, false));
        const float* ch[3] = {image.find("R")->data.data(), image.find("G")->data.data(), image.find("B")->data.data()};
        for (size_t p = 0; p < n; ++p)
            for (int c = 0; c < 3; ++c) rgba[4 * p + c] = tm(ch[c][p] * scale);
        return;
    }
    if (aov_ == Aov::Radiance) {  // from the sums directly: the common case, every frame
        const std::vector<double>& s = acc_->sums();
        const double k = scale / acc_->passes();
        for (size_t p = 0; p < n; ++p)
            for (int c = 0; c < 3; ++c) rgba[4 * p + c] = tm(s[p * TS_PASS_FLOATS + TS_PASS_RADIANCE + c] * k);
        return;
    }
    const Image image = aov_image();
    auto put3 = [&](const char* a, const char* b, const char* c, double mul, double add, bool tone) {
        const ImageChannel* ch[3] = {image.find(a), image.find(b), image.find(c)};
        for (size_t p = 0; p < n; ++p)
            for (int i = 0; i < 3; ++i) {
                const double v = ch[i] ? ch[i]->data[p] * mul + add : 0.0;
                rgba[4 * p + i] = tone ? tm(v) : static_cast<uint8_t>(std::lround(255.0 * std::clamp(v, 0.0, 1.0)));
            }
    };
    auto put1 = [&](const std::vector<float>& v) {  // scaled by the maximum finite value
        float hi = 0.0f;
        for (float x : v)
            if (std::isfinite(x)) hi = std::max(hi, x);
        for (size_t p = 0; p < n; ++p) {
            const float x = std::isfinite(v[p]) && hi > 0 ? v[p] / hi : 1.0f;
            rgba[4 * p] = rgba[4 * p + 1] = rgba[4 * p + 2] = static_cast<uint8_t>(std::lround(255.0f * x));
        }
    };
    switch (aov_) {
        case Aov::Albedo: put3("albedo.R", "albedo.G", "albedo.B", 1.0, 0.0, true); break;
        case Aov::Normal: put3("N.X", "N.Y", "N.Z", 0.5, 0.5, false); break;
        case Aov::Error: {
            const std::vector<double> map = metrics::rel_se_map(metrics::rgb_for_metrics(*reference_, options_.reference),
                                                                metrics::rgb_for_metrics(image, "the view"));
            std::vector<float> v(map.begin(), map.end());
            for (float& x : v) x = std::sqrt(x);  // relative error, not its square: more of the range visible
            put1(v);
            break;
        }
        default: {
            const ImageChannel* ch = image.find(aov_ == Aov::Depth ? "Z" : aov_name(aov_));
            if (ch) put1(ch->data);
            break;
        }
    }
}

std::string ViewSession::backend_description() const { return backend_->description(); }

std::vector<std::string> ViewSession::hud_lines(double fps) const {
    std::vector<std::string> lines;
    char buf[256];
    const double ms = 1e3 * last_.total;
    const double mrays = last_.rays && last_.total > 0 ? last_.rays / last_.total * 1e-6 : 0.0;
    if (last_rendered_)
        std::snprintf(buf, sizeof buf, "%.1f fps, pass %.1f ms, %.2f Mrays/s", fps, ms, mrays);
    else  // nothing rendered: the window's rate says nothing about the renderer
        std::snprintf(buf, sizeof buf, "idle (%s), last pass %.1f ms, %.2f Mrays/s",
                      paused_ ? "paused" : "all passes accumulated", ms, mrays);
    lines.push_back(buf);
    if (igi_family(settings_.method)) {
        std::snprintf(buf, sizeof buf, "VPLs %.1f | SS+ID %.1f | PM %.1f | filter %.1f | AIS %.1f | cache %.1f ms",
                      1e3 * last_.vpl, 1e3 * last_.surface, 1e3 * last_.media, 1e3 * last_.filter, 1e3 * last_.ais,
                      1e3 * last_.cache);
        lines.push_back(buf);
    }
    std::snprintf(buf, sizeof buf, "method %s on %s", method_name(settings_.method),
                  options_.backend.kind == BackendKind::OpenCL ? "opencl" : "embree");
    lines.push_back(buf);
    lines.push_back("device: " + backend_->description());
    std::snprintf(buf, sizeof buf, "passes %u/%u%s%s, %dx%d, frame %d", passes(), settings_.spp,
                  paused_ ? " (paused)" : "", playing_ ? " (playing)" : "", width_, height_, anim_frame_);
    lines.push_back(buf);
    const uint32_t c = settings_.igi.components;
    std::snprintf(buf, sizeof buf, "components %s%s%s%s | AOV %s | exposure %+.1f | speed %.3g/s",
                  c & TS_COMPONENT_SS ? "SS " : "", c & TS_COMPONENT_ID ? "ID " : "",
                  c & TS_COMPONENT_PM ? "PM " : "", c & TS_COMPONENT_EDGE ? "edge" : "", aov_name(aov_), exposure_,
                  speed_);
    lines.push_back(buf);
    if (budget_ && last_budget_.applied) {  // what the last moving frame used
        const BudgetReport& b = last_budget_;
        std::snprintf(buf, sizeof buf, "budget %.3g fps: scale %.2f (%dx%d), tile %u, %u VPL paths, %u light samples",
                      options_.target_fps, b.scale, b.width, b.height, b.tile, b.vpl_paths, b.shadow_samples);
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
