// The boundary between `tessera view` and its window module, libtessera_view_window.so
// (view/window/view_window.cpp: GLFW, OpenGL, Dear ImGui). `tessera view` loads it with
// dlopen only when it opens a window, so nothing else in the program — not even
// `tessera view --headless` — needs those libraries at run time. Only virtual calls cross
// the boundary, so the module needs no symbol of the executable.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "view/input.h"

namespace tessera::view {

/// Bumped whenever WindowHost changes; the module and the executable must agree.
constexpr int kWindowAbiVersion = 2;

/// tessera_view_window_run's code for a display lost mid-run.
constexpr int kWindowLostDisplay = 2;

/// What the window asks of the program: the frame loop, the image and the HUD.
class WindowHost {
public:
    virtual ~WindowHost() = default;
    virtual int width() const = 0;             ///< image size in pixels (the window's size)
    virtual int height() const = 0;
    virtual std::string title() const = 0;
    virtual void input(const InputEvent& event) = 0;
    /// Runs one frame, `wall_dt` seconds after the previous one.
    virtual void frame(double wall_dt) = 0;
    virtual bool done() const = 0;
    /// Nothing changes until an input event: the window may wait for events.
    virtual bool idle() const = 0;
    /// The frame's image, width × height × 4 bytes (RGBA, sRGB), row 0 at the top.
    virtual const std::vector<uint8_t>& pixels() = 0;
    virtual bool hud_visible() const = 0;
    virtual std::vector<std::string> hud(double fps) = 0;
    /// The frame (0-based) after which the window, HUD included, is read back and given
    /// to window_captured (--screenshot-window); −1 for none.
    virtual int capture_frame() const = 0;
    /// The window's pixels, w × h × 4 bytes (RGBA), row 0 at the top.
    virtual void window_captured(const std::vector<uint8_t>& rgba, int w, int h) = 0;
};

}  // namespace tessera::view

/// The module's entry points (C linkage, looked up with dlsym).
extern "C" {
/// Returns kWindowAbiVersion of the module's build.
int tessera_view_window_abi();
/// Checks that a window can be opened (GLFW initialises, that is a display is there)
/// before the program loads the scene. Returns 0, or non-zero with the reason in `error`.
int tessera_view_window_probe(char* error, size_t error_size);
/// Opens the window and runs host's frame loop until host->done() or the window is
/// closed (or destroyed from outside). Returns 0; kWindowLostDisplay with the reason in
/// `error` when the X server's connection was lost mid-run (the frames so far stand); or
/// another non-zero code with a one-line reason in `error` (no display, no OpenGL
/// context).
int tessera_view_window_run(tessera::view::WindowHost* host, char* error, size_t error_size);
}
