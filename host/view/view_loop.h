// The viewer's frame loop without a window: per displayed frame it applies the input
// script's events and the camera path's camera, advances the session by one frame,
// and records the frame (camera path recording, per-frame images and times). The window
// (view/window/) and `tessera view --headless` both run it, so a fly-through gives the
// same images in either.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "view/camera_path.h"
#include "view/input.h"
#include "view/view_session.h"

namespace tessera::view {

struct LoopOptions {
    std::vector<ScriptedEvent> script;        ///< --input-script
    std::vector<PathFrame> path;              ///< --camera-path to replay (empty: none)
    std::filesystem::path record;             ///< --camera-path to record into ("" : none)
    std::filesystem::path frame_images;       ///< directory for frame.####.exr of each frame ("" : none)
    int frame_image_digits = 4;               ///< digits of their numbers (frame_digits of the last one)
    std::filesystem::path times;              ///< per-frame times as JSON ("" : none)
    bool fixed_dt = false;                    ///< move by 1/30 s per frame (scripts, replays) instead of wall time
    bool headless = false;                    ///< stop after the last scripted event when there is no path
};

/// One frame's record in the times file.
struct FrameTime {
    int frame = 0;
    double seconds = 0;     ///< ViewSession::advance, restart and pass included
    FrameReport report;
};

class ViewLoop {
public:
    ViewLoop(ViewSession& session, LoopOptions options);

    /// True when the session asked to quit, the replayed path has ended, or (headless,
    /// no path) the input script's last event has passed.
    bool done() const;
    /// Runs frame frame(): `wall_dt` seconds since the previous (ignored with fixed_dt).
    void step(double wall_dt);
    int frame() const { return frame_; }
    /// True while scripted events or path frames are still to come.
    bool scripted() const {
        return next_event_ < options_.script.size() || frame_ < static_cast<int>(options_.path.size());
    }
    const std::vector<FrameTime>& times() const { return times_; }

    /// Writes the recorded camera path and the times file, and prints a summary line on
    /// stderr (frames, mean moving-frame time and rate). Call once, after the last frame.
    void finish(const std::string& scene_name) const;

private:
    ViewSession& session_;
    LoopOptions options_;
    size_t next_event_ = 0;
    int frame_ = 0;
    std::vector<PathFrame> recorded_;
    std::vector<FrameTime> times_;
};

}  // namespace tessera::view
