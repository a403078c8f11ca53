// Running a shell command or the tessera executable from a test (the CLI tests and the
// bench scripts, which are Python, driven end to end).
#pragma once
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace tessera::test {

/// Runs `cmd` through /bin/sh; its exit status, or -1 if it did not exit normally.
inline int shell_status(const std::string& cmd) {
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

struct CliResult {
    int exit_code;       ///< the exit status, or -1 if the command did not exit normally
    std::string output;  ///< stdout and stderr together
};

/// Runs `cmd` through /bin/sh with stderr joined to stdout and captures both.
inline CliResult run_shell(const std::string& cmd) {
    FILE* p = ::popen((cmd + " 2>&1").c_str(), "r");
    std::string out;
    std::array<char, 4096> buf;
    while (size_t n = std::fread(buf.data(), 1, buf.size(), p)) out.append(buf.data(), n);
    const int status = ::pclose(p);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

#ifdef TESSERA_EXE
/// Runs the tessera executable with `args` (shell words), after the environment
/// assignments `env` ("" for none, e.g. "TESSERA_CL_MAX_ALLOC=64").
inline CliResult run_tessera(const std::string& args, const std::string& env = "") {
    return run_shell(env + (env.empty() ? "" : " ") + std::string(TESSERA_EXE) + " " + args);
}
#endif

}  // namespace tessera::test
