// A fuzzer process's scratch directory in $TMPDIR, tessera-fuzz<suffix>-<pid>, made on first
// use and removed when the process exits (a fuzzing run of -max_total_time returns through
// exit(), which runs static destructors; each CI run otherwise left one per fuzzer).
#pragma once
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace tessera::fuzz {

inline const std::filesystem::path& scratch_dir(const std::string& suffix) {
    struct Dir {
        explicit Dir(const std::string& suffix)
            : path(std::filesystem::temp_directory_path() /
                   ("tessera-fuzz" + suffix + "-" + std::to_string(::getpid()))) {
            std::filesystem::create_directories(path);
        }
        ~Dir() {
            std::error_code ec;
            std::filesystem::remove_all(path, ec);
        }
        std::filesystem::path path;
    };
    static const Dir dir(suffix);
    return dir.path;
}

}  // namespace tessera::fuzz
