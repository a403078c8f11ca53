// Running an external metric tool (a Python script: bench/flip_metric.py,
// bench/cvvdp_metric.py) as a subprocess and capturing what it prints.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace tessera::metrics {

/// What a finished tool run gave.
struct ToolRun {
    bool started = false;  ///< false: the program could not be started (spawn_error says why)
    std::string spawn_error;
    int exit_code = -1;    ///< the exit status; -1 if it did not exit normally (a signal)
    std::string out, err;  ///< its stdout and stderr
};

/// Runs `args` (args[0] looked up on PATH; no shell, so paths need no quoting), waits for
/// it and returns its exit status and output. Never throws for a failing program.
ToolRun run_tool(const std::vector<std::string>& args);

/// The last non-empty line of `s` (a Python tool's error message), without the newline.
std::string last_line(std::string s);

/// Why a run of `python script` failed, in one line: the interpreter missing or not
/// started, or the script's last message (its exit status when it printed none).
std::string tool_failure(const std::string& python, const std::filesystem::path& script, const ToolRun& run);

/// $name if set and not empty, else `fallback`.
std::string env_or(const char* name, const std::string& fallback);

}  // namespace tessera::metrics
