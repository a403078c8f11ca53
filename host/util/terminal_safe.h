// Text from input files (OBJ lines, MTL names, JSON keys, paths) that a message quotes,
// made safe for a terminal: the control characters a terminal acts on (ESC starts the
// escape sequences that recolour, retitle or clear it; U+009B is a one-character CSI)
// are written out as escapes, the way JSON values are already quoted.
#pragma once
#include <cstdio>
#include <string>
#include <string_view>

namespace tessera {

/// `text` with its C0 controls other than newline and tab (a build log's lines stay
/// lines), DEL and the C1 controls U+0080..U+009F (UTF-8 C2 80..C2 9F) written as \xNN
/// (C0, DEL) and \u00NN (C1); every other byte, other UTF-8 included, as it is.
inline std::string terminal_safe(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    char buf[8];
    for (size_t i = 0; i < text.size(); ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        const auto next = i + 1 < text.size() ? static_cast<unsigned char>(text[i + 1]) : 0u;
        if ((c < 0x20 && c != '\n' && c != '\t') || c == 0x7f) {
            std::snprintf(buf, sizeof buf, "\\x%02x", c);
            out += buf;
        } else if (c == 0xc2 && next >= 0x80 && next <= 0x9f) {
            std::snprintf(buf, sizeof buf, "\\u%04x", next);
            out += buf;
            ++i;
        } else {
            out += char(c);
        }
    }
    return out;
}

/// Whether `text` prints as itself on one line: terminal_safe() leaves it unchanged and it
/// holds no newline or tab.
inline bool is_printable_line(std::string_view text) {
    return text.find_first_of("\n\t") == std::string_view::npos && terminal_safe(text) == text;
}

}  // namespace tessera
