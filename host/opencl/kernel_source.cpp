#include "opencl/kernel_source.h"

#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <string_view>
#include <utility>
#include <vector>

#include "util/error.h"

namespace tessera {

// Defined in the generated embedded_kernels.cpp.
const std::vector<std::pair<std::string_view, std::string_view>>& embedded_kernel_files();

namespace {

std::string read_one(const std::string& name) {
    if (const char* dir = std::getenv("TESSERA_KERNEL_DIR"); dir && *dir) {
        std::ifstream in(std::string(dir) + "/" + name, std::ios::binary);
        if (!in)
            throw RuntimeError("kernel source " + name + " not found in TESSERA_KERNEL_DIR=" + dir);
        std::ostringstream ss;
        ss << in.rdbuf();
        return ss.str();
    }
    for (const auto& [path, text] : embedded_kernel_files())
        if (path == name) return std::string(text);
    throw RuntimeError("kernel source " + name + " is not embedded in this build");
}

// A line marker: the compiler's messages name kernels/<name> and its own line numbers, not
// a line of the expanded text in the driver's temporary file.
void mark(const std::string& name, size_t line, std::string& out) {
    out += "#line " + std::to_string(line) + " \"kernels/" + name + "\"\n";
}

void expand(const std::string& name, std::set<std::string>& seen, std::string& out) {
    if (!seen.insert(name).second) return;
    std::istringstream in(read_one(name));
    std::string line;
    mark(name, 1, out);
    for (size_t number = 1; std::getline(in, line); ++number) {
        size_t p = line.find_first_not_of(" \t");
        if (p != std::string::npos && line.compare(p, 8, "#include") == 0) {
            size_t a = line.find('"', p), b = line.find('"', a + 1);
            if (a != std::string::npos && b != std::string::npos) {
                expand(line.substr(a + 1, b - a - 1), seen, out);
                mark(name, number + 1, out);
                continue;
            }
        }
        out += line;
        out += '\n';
    }
}

}  // namespace

std::string load_kernel_source(const std::string& name) {
    std::set<std::string> seen;
    std::string out;
    expand(name, seen, out);
    return out;
}

}  // namespace tessera
