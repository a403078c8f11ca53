// Reading a scene file into a JSON document (declared in scene/json_field.h).
#include <fstream>
#include <sstream>

#include "scene/json_field.h"
#include "util/error.h"

namespace tessera::scene_detail {

nlohmann::json parse_json_file(const std::filesystem::path& file) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec))
        throw InputError(file.string() + ": scene file not found");
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    if (!in) throw InputError(file.string() + ": cannot read scene file");
    const std::string s = text.str();
    try {
        return nlohmann::json::parse(s);
    } catch (const nlohmann::json::parse_error& e) {
        // e.byte is 1-based and points just past the offending character; turn it
        // into a line and column for the message.
        const size_t end = std::min(e.byte > 0 ? e.byte - 1 : 0, s.size());
        size_t line = 1, col = 1;
        for (size_t i = 0; i < end; ++i) {
            if (s[i] == '\n') { ++line; col = 1; } else { ++col; }
        }
        throw InputError(file.string() + ":" + std::to_string(line) + ":" + std::to_string(col) +
                         ": malformed JSON (byte " + std::to_string(e.byte) + "): " + e.what());
    } catch (const nlohmann::json::exception& e) {
        // For example a number too large for a double (out_of_range.406).
        throw InputError(file.string() + ": malformed JSON: " + e.what());
    }
}

}  // namespace tessera::scene_detail
