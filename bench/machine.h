// The machine a benchmark ran on, for the "Machine:" line of its report: the CPU model
// from /proc/cpuinfo and the hardware threads TBB uses. Reports compare only within one
// machine, so each says which.
#pragma once

#include <fstream>
#include <string>

#include <tbb/info.h>

namespace tessera::bench {

/// The CPU's model name from /proc/cpuinfo ("unknown CPU" where it has none).
inline std::string cpu_model() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    return "unknown CPU";
}

/// "<CPU model>, <N> hardware threads".
inline std::string machine_description() {
    return cpu_model() + ", " + std::to_string(tbb::info::default_concurrency()) + " hardware threads";
}

}  // namespace tessera::bench
