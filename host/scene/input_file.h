// Checks and reads an input file (scene, OBJ, MTL, texture) so that every kind of
// "cannot use this path" gets one message naming the file and the reason.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>

namespace tessera::scene_detail {

/// Throws InputError "<file>: <what> not found" when nothing exists at `file`,
/// "<file>: <what> is a directory, not a file" for a directory, and
/// "<file>: <what> is not a regular file" for anything else that is not a file
/// (a socket, a device). `what` names the role, e.g. "OBJ file", "texture".
void require_regular_file(const std::filesystem::path& file, const std::string& what);

/// The bytes of `file` after require_regular_file(); throws InputError
/// "<file>: cannot read <what>" when it cannot be opened or read (permissions), and
/// "<file>: <what> of N bytes exceeds the limit of M" when it is larger than `max_bytes`
/// (util/input_limits.h), before reading any of it.
std::string read_input_file(const std::filesystem::path& file, const std::string& what, std::uintmax_t max_bytes);

}  // namespace tessera::scene_detail
