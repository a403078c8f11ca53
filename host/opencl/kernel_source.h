// OpenCL C sources. By default they come from the copies embedded in the binary at
// build time (cmake/EmbedKernels.cmake), so `tessera` runs from any directory; with
// TESSERA_KERNEL_DIR set they are read from that directory instead, for development
// without rebuilding.
#pragma once
#include <string>

namespace tessera {

/// Returns the source of `name` (a path relative to kernels/, e.g. "direct.cl") with
/// every `#include "x"` replaced by the text of kernels/x, recursively, each file at
/// most once (the headers are guarded anyway). The result needs no include path, so
/// the program builds the same from embedded and from on-disk sources. `#line` markers
/// keep each file's own name ("kernels/shared/compat.h") and line numbers, for the
/// compiler's messages.
/// Throws RuntimeError naming the file if a source or an included header is missing.
std::string load_kernel_source(const std::string& name);

}  // namespace tessera
