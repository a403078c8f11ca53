// Error types for Tessera: every user-facing failure becomes one of these and is
// reported by main() as a single line "tessera: error: <what>" with a non-zero exit.
#pragma once
#include <stdexcept>
#include <string>

namespace tessera {

/// Bad user input: a file that is missing or malformed, or a setting out of range.
/// The message must name the file (with line where known) or the setting.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// A failure of the runtime environment: no OpenCL platform, kernel build failure,
/// an allocation the device refuses, an unwritable output path.
struct RuntimeError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace tessera
