#include "view/input.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include <nlohmann/json.hpp>

#include "scene/json_field.h"
#include "util/error.h"
#include "util/input_limits.h"

namespace tessera::view {

int key_code(const std::string& name) {
    if (name == "space") return ' ';
    if (name == "escape") return kKeyEscape;
    if (name.size() == 1 && std::isprint(static_cast<unsigned char>(name[0])) && name[0] != ' ')
        return std::toupper(static_cast<unsigned char>(name[0]));
    return -1;
}

namespace {

using scene_detail::JsonField;

constexpr float kMaxDragPixels = 1e5f;  // a drag larger than any window (16384 px) by 6x
constexpr const char* kDragRange = "-100000..100000 pixels";
constexpr float kMaxScrollNotches = 100.0f;  // 1.25^100 = 5e9: any speed change a user can want

int parse_key(const JsonField& v) {
    const int code = key_code(v.string());
    if (code < 0) v.fail("a key is one character, \"space\" or \"escape\"");
    return code;
}

// A finite number with |x| <= bound; `range` says the bound in words for the message.
float bounded(const JsonField& v, float bound, const char* range) {
    const float x = v.number();
    if (std::fabs(x) > bound) v.fail(std::string("must be within ") + range);
    return x;
}

// One entry: "frame" and exactly one action, so that no action is silently dropped.
void read_event(const JsonField& e, std::vector<ScriptedEvent>& events) {
    static constexpr const char* kActions[] = {"press", "release", "tap", "drag", "scroll", "quit"};
    e.require_known_keys({"frame", "press", "release", "tap", "drag", "scroll", "quit"});
    const JsonField frame = e["frame"];
    ScriptedEvent s;
    s.frame = frame.integer();
    if (s.frame < 0 || s.frame >= limits::kViewFrames)
        frame.fail("must be a viewer frame in 0.." + std::to_string(limits::kViewFrames - 1));
    std::vector<const char*> given;
    for (const char* a : kActions)
        if (e.find(a)) given.push_back(a);
    if (given.size() != 1)
        e.fail(given.empty() ? "needs one of \"press\", \"release\", \"tap\", \"drag\", \"scroll\", \"quit\""
                             : std::string("has both \"") + given[0] + "\" and \"" + given[1] +
                                   "\"; give one action per entry");
    const std::string action = given[0];
    const JsonField v = e[given[0]];
    using K = InputEvent::Kind;
    if (action == "press") {
        s.event = {K::Press, parse_key(v)};
    } else if (action == "release") {
        s.event = {K::Release, parse_key(v)};
    } else if (action == "tap") {
        s.event = {K::Press, parse_key(v)};
        events.push_back(s);
        s.event.kind = K::Release;
    } else if (action == "drag") {
        if (v.size() != 2) v.fail("\"drag\" must be [dx, dy] in pixels");
        s.event = {K::Drag, 0, bounded(v.at(0), kMaxDragPixels, kDragRange), bounded(v.at(1), kMaxDragPixels, kDragRange)};
    } else if (action == "scroll") {
        s.event = {K::Scroll, 0, 0.0f, bounded(v, kMaxScrollNotches, "-100..100 notches")};
    } else {
        if (!v.raw().is_boolean() || !v.raw().get<bool>()) v.fail("\"quit\" must be true (leave the entry out not to quit)");
        s.event = {K::Quit};
    }
    events.push_back(s);
}

std::vector<ScriptedEvent> read_events(const std::filesystem::path& path) {
    const nlohmann::json doc = scene_detail::parse_json_file(path, "input script");
    const JsonField root(doc, path, "");
    root.require_known_keys({"events"});
    const JsonField list = root["events"];
    // As a camera path needs a camera: an empty script steers nothing (a headless run of
    // one drew no frame, wrote nothing and exited 0).
    if (list.size() == 0) list.fail("an input script needs at least one event");
    if (list.size() > limits::kPathEntries)
        list.fail("more than " + std::to_string(limits::kPathEntries) + " events (the limit for a script)");
    std::vector<ScriptedEvent> events;
    for (size_t i = 0; i < list.size(); ++i) read_event(list.at(i), events);
    std::stable_sort(events.begin(), events.end(),
                     [](const ScriptedEvent& a, const ScriptedEvent& b) { return a.frame < b.frame; });
    return events;
}

}  // namespace

std::vector<ScriptedEvent> read_input_script(const std::filesystem::path& path) {
    try {
        return read_events(path);
    } catch (const InputError& e) {
        throw InputError(std::string("--input-script ") + e.what());
    }
}

}  // namespace tessera::view
