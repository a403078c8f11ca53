#include "view/input.h"

#include <algorithm>
#include <cctype>
#include <fstream>

#include <nlohmann/json.hpp>

#include "util/error.h"

namespace tessera::view {

int key_code(const std::string& name) {
    if (name == "space") return ' ';
    if (name == "escape") return kKeyEscape;
    if (name.size() == 1 && std::isprint(static_cast<unsigned char>(name[0])) && name[0] != ' ')
        return std::toupper(static_cast<unsigned char>(name[0]));
    return -1;
}

namespace {

int parse_key(const nlohmann::json& v, const std::string& where) {
    const int code = v.is_string() ? key_code(v.get<std::string>()) : -1;
    if (code < 0) throw InputError(where + ": key " + v.dump() + " is not one character, \"space\" or \"escape\"");
    return code;
}

float parse_number(const nlohmann::json& v, const std::string& where) {
    if (!v.is_number()) throw InputError(where + ": expected a number, got " + v.dump());
    return v.get<float>();
}

}  // namespace

std::vector<ScriptedEvent> read_input_script(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) throw InputError("--input-script " + path.string() + ": cannot open the file");
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        throw InputError("--input-script " + path.string() + ": not valid JSON (" + e.what() + ")");
    }
    if (!doc.is_object() || !doc.contains("events") || !doc["events"].is_array())
        throw InputError("--input-script " + path.string() + ": expected an object with an \"events\" array");
    std::vector<ScriptedEvent> events;
    for (size_t i = 0; i < doc["events"].size(); ++i) {
        const nlohmann::json& e = doc["events"][i];
        const std::string where = "--input-script " + path.string() + ": events[" + std::to_string(i) + "]";
        if (!e.is_object() || !e.contains("frame") || !e["frame"].is_number_integer() || e["frame"].get<int>() < 0)
            throw InputError(where + ": needs \"frame\", an integer >= 0");
        ScriptedEvent s;
        s.frame = e["frame"].get<int>();
        using K = InputEvent::Kind;
        if (e.contains("press")) {
            s.event = {K::Press, parse_key(e["press"], where)};
        } else if (e.contains("release")) {
            s.event = {K::Release, parse_key(e["release"], where)};
        } else if (e.contains("tap")) {
            s.event = {K::Press, parse_key(e["tap"], where)};
            events.push_back(s);
            s.event.kind = K::Release;
        } else if (e.contains("drag")) {
            const nlohmann::json& d = e["drag"];
            if (!d.is_array() || d.size() != 2) throw InputError(where + ": \"drag\" must be [dx, dy]");
            s.event = {K::Drag, 0, parse_number(d[0], where), parse_number(d[1], where)};
        } else if (e.contains("scroll")) {
            s.event = {K::Scroll, 0, 0.0f, parse_number(e["scroll"], where)};
        } else if (e.contains("quit")) {
            s.event = {K::Quit};
        } else {
            throw InputError(where + ": needs one of \"press\", \"release\", \"tap\", \"drag\", \"scroll\", \"quit\"");
        }
        events.push_back(s);
    }
    std::stable_sort(events.begin(), events.end(),
                     [](const ScriptedEvent& a, const ScriptedEvent& b) { return a.frame < b.frame; });
    return events;
}

}  // namespace tessera::view
