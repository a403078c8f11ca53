#include "scene/obj_text.h"

#include <cerrno>
#include <cstdlib>

#include "util/error.h"

namespace tessera::scene_detail {

namespace {

bool blank(char c) { return c == ' ' || c == '\t'; }
bool digit(char c) { return c >= '0' && c <= '9'; }

// Digits from s[i]; returns how many.
size_t digits(std::string_view s, size_t& i) {
    const size_t start = i;
    while (i < s.size() && digit(s[i])) ++i;
    return i - start;
}

}  // namespace

void line_error(const std::filesystem::path& file, size_t line, const std::string& what) {
    throw InputError(file.string() + ":" + std::to_string(line) + ": " + what);
}

std::vector<TextLine> text_lines(const std::filesystem::path& file, std::string_view text) {
    // tinyobjloader, which parses the file after this scan, reads a byte-order mark as part
    // of the first keyword ("\xEF\xBB\xBFv" is no vertex): every later index would shift.
    if (text.substr(0, 3) == "\xEF\xBB\xBF")
        line_error(file, 1, "starts with a UTF-8 byte-order mark, which the OBJ/MTL parser reads as part of the "
                            "first statement; save the file without it (as plain UTF-8 or ASCII)");
    std::vector<TextLine> lines;
    size_t number = 0;
    for (size_t pos = 0; pos < text.size();) {
        size_t end = pos;
        while (end < text.size() && text[end] != '\n' && text[end] != '\r') ++end;
        ++number;
        std::string_view line = text.substr(pos, end - pos);
        const bool crlf = end + 1 < text.size() && text[end] == '\r' && text[end + 1] == '\n';
        pos = end + (crlf ? 2 : 1);
        if (line.find('\0') != std::string_view::npos)
            line_error(file, number, "contains a NUL byte (this is not a text file)");
        while (!line.empty() && blank(line.front())) line.remove_prefix(1);
        while (!line.empty() && blank(line.back())) line.remove_suffix(1);
        if (line.empty() || line.front() == '#') continue;
        TextLine l;
        l.number = number;
        l.text = line;
        for (size_t i = 0; i < line.size();) {
            while (i < line.size() && blank(line[i])) ++i;
            const size_t start = i;
            while (i < line.size() && !blank(line[i])) ++i;
            if (i > start) l.tokens.push_back(line.substr(start, i - start));
        }
        lines.push_back(std::move(l));
    }
    return lines;
}

std::vector<std::string_view> value_tokens(const TextLine& line, size_t first) {
    std::vector<std::string_view> out;
    for (size_t i = first; i < line.tokens.size() && line.tokens[i].front() != '#'; ++i)
        out.push_back(line.tokens[i]);
    return out;
}

bool parse_real(std::string_view s, double& value) {
    size_t i = 0;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    const size_t int_digits = digits(s, i);
    size_t frac_digits = 0;
    if (i < s.size() && s[i] == '.') {
        ++i;
        frac_digits = digits(s, i);
    }
    if (int_digits + frac_digits == 0) return false;
    if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
        ++i;
        if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
        if (digits(s, i) == 0) return false;
    }
    if (i != s.size()) return false;
    // The grammar above is a subset of strtod's, so strtod reads the whole token.
    value = std::strtod(std::string(s).c_str(), nullptr);
    return true;
}

bool parse_index(std::string_view s, long long& value, bool& overflow) {
    size_t i = 0;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    if (digits(s, i) == 0 || i != s.size()) return false;
    errno = 0;
    value = std::strtoll(std::string(s).c_str(), nullptr, 10);
    overflow = errno == ERANGE;
    return true;
}

}  // namespace tessera::scene_detail
