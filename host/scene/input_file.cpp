#include "scene/input_file.h"

#include <fstream>
#include <sstream>
#include <system_error>

#include "util/error.h"

namespace tessera::scene_detail {

namespace fs = std::filesystem;

void require_regular_file(const fs::path& file, const std::string& what) {
    std::error_code ec;
    const fs::file_status st = fs::status(file, ec);
    if (!fs::exists(st)) throw InputError(file.string() + ": " + what + " not found");
    if (fs::is_directory(st)) throw InputError(file.string() + ": " + what + " is a directory, not a file");
    if (!fs::is_regular_file(st)) throw InputError(file.string() + ": " + what + " is not a regular file");
}

std::string read_input_file(const fs::path& file, const std::string& what, std::uintmax_t max_bytes) {
    require_regular_file(file, what);
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(file, ec);
    if (!ec && size > max_bytes)
        throw InputError(file.string() + ": " + what + " of " + std::to_string(size) + " bytes exceeds the limit of " +
                         std::to_string(max_bytes) + " bytes");
    std::ifstream in(file, std::ios::binary);
    if (!in) throw InputError(file.string() + ": cannot read " + what + " (permission denied?)");
    std::ostringstream text;
    text << in.rdbuf();  // an empty file sets failbit on `text` only: empty is valid here
    return text.str();
}

}  // namespace tessera::scene_detail
