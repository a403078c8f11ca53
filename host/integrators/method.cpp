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

bool igi_family(Method m) { return m != Method::Direct && m != Method::PathTrace; }

uint32_t parse_components(const std::string& list) {
    uint32_t bits = 0;
    size_t start = 0;
    while (start <= list.size()) {
        const size_t end = std::min(list.find(',', start), list.size());
        const std::string c = list.substr(start, end - start);
        const uint32_t bit = c == "ss"     ? TS_COMPONENT_SS
                             : c == "id"   ? TS_COMPONENT_ID
                             : c == "pm"   ? TS_COMPONENT_PM
                             : c == "edge" ? TS_COMPONENT_EDGE
                                           : 0;
        if (bit == 0)
            throw InputError("--components " + list + ": expected a comma-separated list of ss, id, pm, edge" +
                             (c.empty() ? " (an entry is empty)" : ", got '" + c + "'"));
        if (bits & bit) throw InputError("--components " + list + ": '" + c + "' is listed twice");
        bits |= bit;
        start = end + 1;
    }
    return bits;
}

}  // namespace tessera
