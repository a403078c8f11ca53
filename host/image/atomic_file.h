// Atomic file replacement: content goes to a unique temporary file in the target's
// directory, which is renamed over the target only after a complete, synced write.
#pragma once
#include <cstddef>
#include <filesystem>
#include <functional>

namespace tessera {

/// Writes `size` bytes atomically to `path`. Throws RuntimeError naming `path` and the
/// OS reason on failure; an existing file at `path` is then left untouched.
void write_file_atomic(const std::filesystem::path& path, const void* data, std::size_t size);

/// Creates a unique empty temporary file `.<name>.tmp.XXXXXX` beside `path`, calls
/// `write(temp)` to fill it (the callback may reopen the file by name), fsyncs it and
/// renames it over `path`. On any failure (including an exception from `write`) the
/// temporary is removed; OS failures throw RuntimeError naming `path`, exceptions from
/// `write` propagate unchanged.
void replace_file_atomic(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path& temp)>& write);

}  // namespace tessera
