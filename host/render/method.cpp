#include "render/method.h"

#include "util/error.h"

namespace tessera {

Method parse_method(const std::string& name) {
    if (name == "direct") return Method::Direct;
    if (name == "pt") return Method::PathTrace;
    throw InputError("--method " + name + ": not available (implemented: direct, pt)");
}

const char* method_name(Method m) { return m == Method::Direct ? "direct" : "pt"; }

}  // namespace tessera
