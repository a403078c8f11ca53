// Error types for Tessera: every user-facing failure becomes one of these and is
// reported by main() as a single line "tessera: error: <what>" with a non-zero exit.
#pragma once
#include <cstdint>
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

/// An OpenCL program that did not build (the message holds the build log). Its own type
/// because PoCL's LLVM handles SIGINT/SIGTERM first while it compiles, deleting its
/// temporary files, so a Ctrl-C during a build fails it: the command reports that as the
/// interrupt it is.
struct BuildError : RuntimeError {
    using RuntimeError::RuntimeError;
};

/// A render stopped by SIGINT or SIGTERM, after its state was saved to a checkpoint
/// (render/checkpoint.h) or with a message saying why none was. main() prints "tessera: <what>" and exits with status 130.
struct Interrupted : std::runtime_error {
    Interrupted(uint32_t done, uint32_t total, const std::string& checkpoint)
        : std::runtime_error("interrupted after " + std::to_string(done) + " of " + std::to_string(total) +
                             " spp; checkpoint saved to " + checkpoint + "; resume with --resume"),
          passes_done(done), passes_total(total) {}
    /// Stopped with no checkpoint: `message` says so and why ("... no checkpoint written: ...").
    explicit Interrupted(const std::string& message) : std::runtime_error(message), passes_done(0), passes_total(0) {}
    uint32_t passes_done, passes_total;
};

}  // namespace tessera
