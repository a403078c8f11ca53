// Reading a scene file into a JSON document (declared in scene/json_field.h).
#include <cctype>
#include <cstdio>
#include <set>
#include <vector>

#include "scene/input_file.h"
#include "scene/json_field.h"
#include "util/error.h"
#include "util/input_limits.h"

namespace tessera::scene_detail {

namespace {

using json = nlohmann::json;

// Follows the parser through the document to know the key path of the value being read,
// for duplicate keys (which nlohmann::json would silently resolve to the last value), for
// a number that overflows (which its exception does not place) and for nesting deeper
// than limits::kJsonDepth. Each level keeps its own key or index only: the path is put
// together when a message needs it, so memory grows with the depth, not its square.
class KeyTracker {
public:
    explicit KeyTracker(const std::filesystem::path& file) : file_(file) {}

    bool event(json::parse_event_t event, const json& parsed) {
        switch (event) {
            case json::parse_event_t::object_start:
            case json::parse_event_t::array_start:
                if (frames_.size() >= size_t(limits::kJsonDepth))
                    throw InputError(file_.string() + ": " + where(current_path()) + ": JSON nested deeper than " +
                                     std::to_string(limits::kJsonDepth) + " levels (the limit for any input file)");
                frames_.push_back({event == json::parse_event_t::array_start, 0, {}, {}});
                break;
            case json::parse_event_t::object_end:
            case json::parse_event_t::array_end:
                frames_.pop_back();
                advance();
                break;
            case json::parse_event_t::key: {
                Frame& f = frames_.back();
                f.key = parsed.get<std::string>();
                // A NUL would end the key in every message that names it (as for values,
                // JsonField::string): refused here, shown escaped.
                if (f.key.find('\0') != std::string::npos) {
                    const std::string key = json(f.key).dump();
                    f.key.clear();  // the path of the object that holds it
                    std::string in = current_path();
                    if (!in.empty() && in.back() == '.') in.pop_back();
                    throw InputError(file_.string() + ": key " + key + " in " +
                                     (in.empty() ? std::string("the top level") : "'" + in + "'") +
                                     ": must not contain a NUL character (\\u0000)");
                }
                if (!f.keys.insert(f.key).second)
                    throw InputError(file_.string() + ": duplicate key '" + current_path() +
                                     "' (a key may appear once in an object)");
                break;
            }
            case json::parse_event_t::value:
                advance();
                break;
        }
        return true;
    }

    /// The path of the value the parser is reading now ("" at the top level), e.g.
    /// "objects[2].transform"; a path past 120 characters keeps its start and ends in "...".
    std::string current_path() const {
        std::string p;
        for (const Frame& f : frames_) {
            if (p.size() > 120) return p.substr(0, 117) + "...";
            if (f.array) p += "[" + std::to_string(f.next) + "]";
            else p += (p.empty() ? "" : ".") + f.key;
        }
        return p.size() > 120 ? p.substr(0, 117) + "..." : p;
    }

private:
    struct Frame {
        bool array;
        size_t next;                 // index of the element being read (arrays)
        std::string key;             // the last key read (objects)
        std::set<std::string> keys;  // keys read so far (objects)
    };

    static std::string where(const std::string& path) { return path.empty() ? "top level" : "key '" + path + "'"; }

    // A value or a nested array/object has ended: the enclosing array moves to its next element.
    void advance() {
        if (!frames_.empty() && frames_.back().array) ++frames_.back().next;
    }

    const std::filesystem::path& file_;
    std::vector<Frame> frames_;
};

// nlohmann::json's parse_error text is "[json.exception.parse_error.101] parse error at
// line 3, column 5: syntax error while parsing ..."; keep only what follows the location.
std::string parse_error_reason(const std::string& what) {
    const size_t column = what.find("column ");
    const size_t colon = what.find(": ", column == std::string::npos ? 0 : column);
    return colon == std::string::npos ? what : what.substr(colon + 2);
}

// `text` with every byte outside printable ASCII written \xNN: the parser quotes what it
// last read, and a raw byte of invalid UTF-8 would reach the terminal as it is.
std::string printable(const std::string& text) {
    std::string out;
    for (const unsigned char c : text) {
        if (c >= 0x20 && c < 0x7f) {
            out += static_cast<char>(c);
        } else {
            char hex[8];
            std::snprintf(hex, sizeof hex, "\\x%02x", c);
            out += hex;
        }
    }
    return out;
}

// A hint where the file is a mesh, not a scene: its name ends in .obj or .mtl.
std::string mesh_hint(const std::filesystem::path& file) {
    std::string ext = file.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".obj" && ext != ".mtl") return "";
    return " (" + file.filename().string() +
           " is a mesh file: a scene is a JSON file that names its meshes under \"objects\", scenes/README.md)";
}

}  // namespace

json parse_json_file(const std::filesystem::path& file, const std::string& what) {
    const std::string s = read_input_file(file, what, limits::kJsonFileBytes);
    KeyTracker tracker(file);
    try {
        return json::parse(s, [&](int, json::parse_event_t event, json& parsed) {
            return tracker.event(event, parsed);
        });
    } catch (const json::parse_error& e) {
        // e.byte is 1-based and points just past the offending character; turn it
        // into a line and column for the message.
        const size_t end = std::min(e.byte > 0 ? e.byte - 1 : 0, s.size());
        size_t line = 1, col = 1;
        for (size_t i = 0; i < end; ++i) {
            if (s[i] == '\n') { ++line; col = 1; } else { ++col; }
        }
        throw InputError(file.string() + ":" + std::to_string(line) + ":" + std::to_string(col) +
                         ": malformed JSON: " + printable(parse_error_reason(e.what())) + mesh_hint(file));
    } catch (const json::out_of_range& e) {
        // A number literal too large for a double (1e999): nlohmann::json reports
        // "number overflow parsing '<literal>'" (out_of_range.406) without a place.
        const std::string what = e.what();
        const size_t quote = what.find('\'');
        const std::string literal = quote == std::string::npos ? "" : " " + what.substr(quote);
        const std::string key = tracker.current_path();
        throw InputError(file.string() + ": " + (key.empty() ? "top level" : "key '" + key + "'") +
                         ": number" + literal + " overflows a double (numbers must be finite)");
    } catch (const json::exception& e) {
        throw InputError(file.string() + ": malformed JSON: " + printable(parse_error_reason(e.what())) +
                         mesh_hint(file));
    }
}

}  // namespace tessera::scene_detail
