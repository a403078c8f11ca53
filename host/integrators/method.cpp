#include "integrators/method.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "device/components.h"
#include "kernels/shared/layout_igi.h"
#include "util/error.h"

namespace tessera {

const MethodInfo& method_info(Method m) {
    const std::vector<MethodInfo>& table = method_table();
    const size_t i = static_cast<size_t>(m);
    if (i >= table.size() || table[i].method != m) throw std::logic_error("method_table(): no row in Method order for a method");
    return table[i];
}

Method parse_method(const std::string& name) {
    for (const MethodInfo& row : method_table())
        if (name == row.name) return row.method;
    throw InputError("--method " + name + ": not available (implemented: " + method_names() + ")");
}

const char* method_name(Method m) { return method_info(m).name; }

std::string method_names() {
    std::string names;
    for (const MethodInfo& row : method_table()) names += std::string(names.empty() ? "" : ", ") + row.name;
    return names;
}

bool igi_family(Method m) { return method_info(m).igi_family; }

namespace {

/// "ss, id, pm, edge": every --components name, for the parser's message.
std::string component_options() {
    std::string out;
    for (const ComponentName& n : kComponentNames) out += (out.empty() ? "" : ", ") + std::string(n.option);
    return out;
}

}  // namespace

uint32_t parse_components(const std::string& list) {
    uint32_t bits = 0;
    size_t start = 0;
    while (start <= list.size()) {
        const size_t end = std::min(list.find(',', start), list.size());
        const std::string c = list.substr(start, end - start);
        uint32_t bit = 0;
        for (const ComponentName& n : kComponentNames)
            if (c == n.option) bit = n.bit;
        if (bit == 0)
            throw InputError("--components " + list + ": expected a comma-separated list of " + component_options() +
                             (c.empty() ? " (an entry is empty)" : ", got '" + c + "'"));
        if (bits & bit) throw InputError("--components " + list + ": '" + c + "' is listed twice");
        bits |= bit;
        start = end + 1;
    }
    return bits;
}

std::string components_text(uint32_t mask) {
    std::string out;
    for (const ComponentName& n : kComponentNames)
        if (mask & n.bit) out += (out.empty() ? "" : ",") + std::string(n.option);
    return out.empty() ? "none" : out;
}

}  // namespace tessera
