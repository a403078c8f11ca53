// ViewSession's input: key, mouse and scroll events to camera moves and switches, and
// the key bindings' help (docs/viewer.md §2).
#include "view/view_session.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "util/input_limits.h"
#include "view/camera_control.h"

namespace tessera::view {
namespace {

constexpr float kTurnPerPixel = 0.004f;   // radians of yaw/pitch per pixel dragged
constexpr float kSpeedStep = 1.25f;       // speed factor per scroll notch
constexpr float kMaxScrollNotches = 100;  // 1.25^100 = 5e9 either way of the start speed
constexpr float kExposureStep = 0.5f;     // stops per [ or ] press

}  // namespace

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
        case 'P': screenshot_pending_ = true, take_pending_screenshot(); break;
        case 'M': switch_method(1); break;
        case 'N': switch_method(-1); break;
        case '1': toggle_component(TS_COMPONENT_SS); break;
        case '2': toggle_component(TS_COMPONENT_ID); break;
        case '3': toggle_component(TS_COMPONENT_PM); break;
        case '4': toggle_component(TS_COMPONENT_EDGE); break;
        case 'V': cycle_aov(1); break;
        case 'B': cycle_aov(-1); break;
        // Kept within the --exposure range (limits::kExposureStops), where 2^exposure is finite.
        case '[': exposure_ = std::max(exposure_ - kExposureStep, float(-limits::kExposureStops)); break;
        case ']': exposure_ = std::min(exposure_ + kExposureStep, float(limits::kExposureStops)); break;
        case ' ': paused_ = !paused_; break;
        case 'T':
            playing_ = !playing_ && options_.last_frame > options_.first_frame;
            if (options_.last_frame > options_.first_frame) break;
            if (rest_.animation.animated())  // else the key would do nothing, silently
                std::fprintf(stderr, "tessera view: T plays the frames of --frames FIRST:LAST (this scene has frames "
                                     "0..%d; this run shows frame %d only)\n", rest_.animation.frame_count - 1,
                             options_.first_frame);
            else
                std::fprintf(stderr, "tessera view: T plays an animation; this scene has none\n");
            break;
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

}  // namespace tessera::view
