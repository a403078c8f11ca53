// Line and number scanning shared by the OBJ and MTL checks (scene/obj_scan.h,
// scene/mtl_scan.h). tinyobjloader parses both formats; these helpers only re-read the
// statements whose values it would silently replace (it reads "nan", "1,5" or "0x10" as
// 0 or as a prefix, and an overflowing face index as -1), so that the loader can reject
// them with the file, line and value.
#pragma once
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace tessera::scene_detail {

/// One non-blank, non-comment line: its 1-based number and its tokens, split on spaces
/// and tabs (the separators tinyobjloader uses), with trailing spaces, tabs and '\r'
/// removed. tokens[0] is the statement keyword ("v", "f", "Kd", ...).
struct TextLine {
    size_t number = 0;
    std::string_view text;                 ///< the line without leading/trailing blanks
    std::vector<std::string_view> tokens;
};

/// Splits `text` into lines at "\n", "\r\n" or "\r" (as tinyobjloader's safeGetline
/// does) and returns those that are neither blank nor comments ('#' first). Throws
/// InputError "<file>:<line>: contains a NUL byte" for a binary file (tinyobjloader
/// would stop reading that line at the NUL).
std::vector<TextLine> text_lines(const std::filesystem::path& file, std::string_view text);

/// The tokens of `line` from `first` up to a token starting with '#' (an end-of-line
/// comment).
std::vector<std::string_view> value_tokens(const TextLine& line, size_t first = 1);

/// Parses a real number written in the grammar tinyobjloader accepts,
/// [+-](digits[.digits] | .digits)[(e|E)[+-]digits], and nothing else: false for
/// "nan", "inf", "0x10", "1,5", "1e" and the like. The value may overflow to ±inf.
bool parse_real(std::string_view token, double& value);

/// Parses an OBJ index, [+-]digits. Returns false when the token is not one;
/// `overflow` is set (and `value` meaningless) when it does not fit a long long.
bool parse_index(std::string_view token, long long& value, bool& overflow);

/// Throws InputError "<file>:<line>: <what>".
[[noreturn]] void line_error(const std::filesystem::path& file, size_t line, const std::string& what);

}  // namespace tessera::scene_detail
