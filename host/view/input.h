// Input events of the viewer, independent of any window system: the window (GLFW) and
// the input script (--input-script) both produce them, and ViewSession consumes them.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace tessera::view {

/// Key codes: printable keys are their upper-case ASCII code ('W', '1', '[', ' ');
/// keys without one have codes above 255.
constexpr int kKeyEscape = 256;

struct InputEvent {
    enum class Kind { Press, Release, Drag, Scroll, Quit };
    Kind kind = Kind::Press;
    int key = 0;           ///< Press, Release: the key code
    float dx = 0, dy = 0;  ///< Drag: mouse motion in pixels (x right, y down) with a button held; Scroll: dy notches
};

/// The key code of a key name: one printable character (case-insensitive: "w" is 'W'),
/// "space" or "escape"; -1 for anything else.
int key_code(const std::string& name);

/// An input event due at a frame of the viewer (0 = the first frame drawn).
struct ScriptedEvent {
    int frame = 0;
    InputEvent event;
};

/// Reads an input script (--input-script): a JSON object {"events": [...]} whose entries
/// are {"frame": F, ACTION} with ACTION one of "press": KEY, "release": KEY, "tap": KEY
/// (press and release in the same frame), "drag": [dx, dy] (pixels, each within
/// +-100000), "scroll": notches (within +-100), "quit": true; exactly one ACTION per entry
/// and F in 0..limits::kViewFrames-1. Events are returned sorted by frame (stable). The
/// whole file is checked first. Throws InputError "--input-script <file>: key
/// 'events[3].quit' = false: <why>" for anything else (an unknown key, a second action,
/// a value out of range, no events or more than limits::kPathEntries) and for the file errors
/// of scene_detail::parse_json_file.
std::vector<ScriptedEvent> read_input_script(const std::filesystem::path& path);

}  // namespace tessera::view
