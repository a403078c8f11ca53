// The rendering methods (--method) and their names.
#pragma once
#include <string>

namespace tessera {

enum class Method {
    Direct,     ///< emission + direct light from area lights (kernels/shared/direct.h)
    PathTrace,  ///< volumetric path tracing, the reference (kernels/shared/pt.h)
};

/// Parses "direct" or "pt"; throws InputError naming --method otherwise.
Method parse_method(const std::string& name);
const char* method_name(Method m);

}  // namespace tessera
