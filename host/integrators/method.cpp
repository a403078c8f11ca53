#include "integrators/method.h"

#include <algorithm>

#include "kernels/shared/layout.h"
#include "util/error.h"

namespace tessera {

Method parse_method(const std::string& name) {
    if (name == "direct") return Method::Direct;
    if (name == "pt") return Method::PathTrace;
    if (name == "igi") return Method::Igi;
    if (name == "ais") return Method::Ais;
    if (name == "ais-max") return Method::AisMax;
    if (name == "ic") return Method::Ic;
    if (name == "tic") return Method::Tic;
    throw InputError("--method " + name + ": not available (implemented: direct, pt, igi, ais, ais-max, ic, tic)");
}

const char* method_name(Method m) {
    switch (m) {
        case Method::Direct: return "direct";
        case Method::PathTrace: return "pt";
        case Method::Igi: return "igi";
        case Method::Ais: return "ais";
        case Method::AisMax: return "ais-max";
        case Method::Ic: return "ic";
        case Method::Tic: return "tic";
    }
    return "?";
}

uint32_t parse_components(const std::string& list) {
    uint32_t bits = 0;
    size_t start = 0;
    while (start <= list.size()) {
        const size_t end = std::min(list.find(',', start), list.size());
        const std::string c = list.substr(start, end - start);
        if (c == "ss") bits |= TS_COMPONENT_SS;
        else if (c == "id") bits |= TS_COMPONENT_ID;
        else if (c == "pm") bits |= TS_COMPONENT_PM;
        else throw InputError("--components " + list + ": expected a comma-separated list of ss, id, pm");
        start = end + 1;
    }
    return bits;
}

}  // namespace tessera
