// The interactive viewer's state without a window (docs/viewer.md): camera, controls,
// progressive accumulation, method and component switches, AOV selection, stage timings
// and the frame-time budget. The window (view/window/) and `tessera view --headless`
// drive it through ViewLoop (view/view_loop.h); tests drive it directly.
//
// Progressive refinement: every change of camera, animation frame, method, components or
// budget settings starts a new accumulation, whose first pass is pass 0 of the method —
// one fresh interleaved frame while the camera moves. At rest, pass k = 1, 2, ... adds new
// VPL sets and light samples, exactly as `tessera render --spp N` renders passes 0..N−1
// (the frame comes from make_render_frame and a fresh integrator per accumulation), so
// the accumulation after N passes at rest equals render's image with the same camera,
// method, settings and seed.
#pragma once
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "backend/backend.h"
#include "device/effect_plan.h"
#include "device/scene_buffers.h"
#include "gi/vpl_importance.h"
#include "image/image_io.h"
#include "integrators/integrator.h"
#include "render/accumulator.h"
#include "render/renderer.h"
#include "scene/posed_frames.h"
#include "scene/scene.h"
#include "view/frame_budget.h"
#include "view/input.h"

namespace tessera::view {

struct ViewOptions {
    BackendOptions backend;
    /// Method, method settings, seed, size (0: the camera's). spp: the passes at which
    /// accumulation at rest stops (the image then equals `render --spp` with them).
    RenderSettings settings;
    float exposure = 0.0f;       ///< display and PNG exposure in stops
    int first_frame = 0;         ///< animation frames the viewer plays (--frames A:B)
    int last_frame = 0;
    std::filesystem::path reference;   ///< EXR of the same size for the error AOV ("" for none)
    std::filesystem::path screenshot;  ///< screenshot n goes to frame_output_path(screenshot, n) (+ .png)
    /// Files (same_file() keys) a screenshot must not replace: the run's inputs and its
    /// other outputs. A screenshot number whose EXR or PNG is one of them is skipped.
    std::vector<std::filesystem::path> reserved;
    double target_fps = 0.0;           ///< > 0: moving frames follow the frame-time budget
    std::vector<BudgetPoint> pareto;   ///< candidate settings for the budget (frame_budget.h)
    double pareto_pixels = 0.0;        ///< pixels of the sweep's images (0: unknown), for the first prediction
    double min_scale = BudgetOptions{}.min_scale;  ///< the floor of the budget's per-axis resolution scale (--min-scale)
    float speed = 0.0f;                ///< movement speed, scene units per second; 0: default_speed
};

/// What the AOV key (V) cycles through; the ones a method does not produce are skipped.
enum class Aov { Radiance, Albedo, Normal, Depth, GuidanceSS, GuidanceID, GuidancePM, SetsSS, SetsID, SetsPM, Error };
const char* aov_name(Aov aov);

/// Stage times of the last pass in seconds (IgiFrameStats; 0 for stages a method lacks).
struct StageTimes {
    double vpl = 0, surface = 0, media = 0, filter = 0, ais = 0, edges = 0, cache = 0;
    double total = 0;      ///< the whole pass, integrator and accumulation
    uint64_t rays = 0;     ///< rays the pass traced as the integrator counts them (0: not counted)
};

/// The frame-time budget's choice for a moving frame (all zero when no budget applied).
struct BudgetReport {
    bool applied = false;      ///< the frame was rendered with the budget's choice
    double scale = 1.0;        ///< per-axis resolution scale of the frame
    int width = 0, height = 0; ///< the frame's rendered size (upsampled to the window)
    uint32_t tile = 0, vpl_paths = 0, shadow_samples = 0;
    bool out_of_reach = false; ///< the cheapest choice there is, and the frame still missed the target
    double seconds = 0;        ///< the frame's measured time (integrator set-up and pass)
};

/// What advance() did this frame.
struct FrameReport {
    bool rendered = false;   ///< a pass was rendered (false: paused or all spp accumulated)
    /// The accumulation was restarted this frame by a change (camera, animation or a
    /// switch). False on the run's first frame, which starts it: rendered as a moving
    /// frame is (--target-fps budgets it), but left out of the moving-frame rate, as it
    /// pays first-use costs (bench/interactive leaves it out likewise).
    bool moving = false;
    uint32_t passes = 0;     ///< passes in the accumulation after this frame
    StageTimes stages;
    BudgetReport budget;
};

class ViewSession {
public:
    /// `rest` is the scene at rest (animated scenes are posed per frame). Builds the
    /// backend; throws what make_backend and validate_settings throw, and InputError
    /// naming --reference when the reference cannot be read or has another size.
    ViewSession(const Scene& rest, const ViewOptions& options);
    ~ViewSession();
    // posed_ holds a reference to rest_: a copy or move would leave it on the old one.
    ViewSession(const ViewSession&) = delete;
    ViewSession& operator=(const ViewSession&) = delete;

    /// Applies one input event (key bindings: key_help()).
    void handle(const InputEvent& event);

    /// One displayed frame `dt` seconds after the last: moves the camera by the held keys,
    /// plays the animation, restarts the accumulation when anything changed, and renders
    /// one pass unless paused or spp passes are accumulated.
    FrameReport advance(double dt);

    const Camera& camera() const { return camera_; }
    /// Sets the camera (camera paths); the viewer's resolution is kept.
    void set_camera(const Camera& camera);
    int animation_frame() const { return anim_frame_; }
    /// Shows animation frame `frame` (camera paths); throws InputError outside --frames.
    void set_animation_frame(int frame);

    int width() const { return width_; }
    int height() const { return height_; }
    uint32_t passes() const { return acc_ ? acc_->passes() : 0; }
    /// > 0 when moving frames follow a frame-time budget (--target-fps).
    double target_fps() const { return budget_ ? options_.target_fps : 0.0; }
    bool quit_requested() const { return quit_; }
    bool hud_visible() const { return hud_visible_; }
    /// Nothing to render until an input arrives: paused, or all spp passes accumulated
    /// with no key held and no animation playing (the window then waits for events).
    bool idle() const {
        return paused_ || (acc_ && !dirty_ && acc_->passes() >= settings_.spp && held_.empty() && !playing_);
    }
    Method method() const { return settings_.method; }

    /// The accumulation as `tessera render` writes it: R, G, B and variance.R/G/B (and
    /// the AOV channels when settings.aovs), at the window's size: a moving frame that the
    /// budget rendered at a lower resolution is upsampled bilinearly (image/resample.h).
    Image accumulation() const;
    /// Writes the accumulation as EXR + PNG (atomic, both or neither) to the next
    /// screenshot path; returns the EXR path. Prints the EXR path on stdout and the pass
    /// count on stderr ("tessera view: screenshot of N passes: PATH").
    std::filesystem::path save_screenshot();
    /// Emissive triangles on a light facing the same way (SceneBuffers::stacked_emitters).
    uint32_t stacked_emitters() const { return buffers_->stacked_emitters; }
    /// Whether `file` is one of ViewOptions::reserved (a file the run reads or writes).
    bool reserved(const std::filesystem::path& file) const;
    void take_pending_screenshot();  ///< P: now, or after the first pass when there is none yet

    /// The selected AOV tone-mapped for display: width × height × 4 bytes (RGBA, sRGB,
    /// alpha 255), row 0 at the top.
    void display(std::vector<uint8_t>& rgba) const;

    /// The heads-up display's lines: fps, stage times, rays/s, method, backend, passes,
    /// components, AOV and budget settings (resolution scale included, and a line when the
    /// target is out of reach). `fps` is the window's measured rate.
    std::vector<std::string> hud_lines(double fps) const;
    /// One line per key binding.
    static std::vector<std::string> key_help();
    std::string backend_description() const;
    /// Mean relMSE of the accumulation against --reference (−1 without one).
    double reference_error() const;

private:
    void build_backend();
    void restart();
    void switch_method(int step);
    void toggle_component(uint32_t bit);
    void cycle_aov(int step);
    bool aov_available(Aov aov) const;
    /// Whether `aov` shows the AIS schedule (guidance, sets), whose sums only the host
    /// path keeps (IgiSettings::component_aovs).
    static bool schedule_aov(Aov aov);
    /// Whether `aov` shows the pass image's albedo, normal or depth, which a frame resolved
    /// on the device brings back only while shown (IgiSettings::pass_aovs).
    static bool pass_aov(Aov aov);
    RenderSettings pass_settings() const;
    Image aov_image() const;
    Image to_window(Image image) const;
    void observe_budget(double frame_seconds, FrameReport& report);

    Scene rest_, scene_;
    PosedFrames posed_{rest_};  ///< rest_'s frames; after rest_, which it reads
    ViewOptions options_;
    RenderSettings settings_;
    int width_ = 0, height_ = 0;
    Camera camera_, home_camera_, acc_camera_;
    int anim_frame_ = 0, acc_anim_frame_ = -1;
    float speed_ = 1.0f, exposure_ = 0.0f;
    float start_speed_ = 1.0f;  ///< the speed at start: scrolling stays within kMaxScrollNotches of it
    std::set<int> held_, pressed_;  // keys down now; keys pressed since the last advance()
    bool dirty_ = true, paused_ = false, playing_ = false, quit_ = false, hud_visible_ = true;
    bool acc_budgeted_ = false;   // the accumulation uses the budget's settings, not settings_
    Aov aov_ = Aov::Radiance;
    int screenshots_ = 0;
    bool screenshot_pending_ = false;  // P before the first pass: taken once one is accumulated
    std::optional<Image> reference_;
    EffectPlan plan_;
    std::unique_ptr<SceneBuffers> buffers_;
    std::unique_ptr<Backend> backend_;
    std::unique_ptr<Integrator> integrator_;
    /// The VPL selection's view points across frames (ViewPointHistory), given to every
    /// integrator the session makes: moving frames restart the integrator, not this.
    std::shared_ptr<ViewPointHistory> view_history_ = std::make_shared<ViewPointHistory>();
    /// The accumulation has a pass rendered with kept (not the camera's own) view points:
    /// at rest it starts over, as after a budgeted frame.
    bool acc_kept_points_ = false;
    std::unique_ptr<Accumulator> acc_;
    TsFrame frame_{};
    std::vector<float> pass_;
    StageTimes last_;
    bool last_rendered_ = false;  // the last advance() rendered a pass
    std::unique_ptr<FrameBudget> budget_;
    BudgetReport last_budget_;
    int render_width_ = 0, render_height_ = 0;  // the accumulation's size (below the window's while moving on a budget)
    int misses_at_cheapest_ = 0;                // consecutive moving frames over the target at the cheapest choice
    bool reach_reported_ = false;               // the out-of-reach line was printed
};

}  // namespace tessera::view
