// Running a shell command from a test (the bench scripts are Python, driven end to end).
#pragma once
#include <sys/wait.h>

#include <cstdlib>
#include <string>

namespace tessera::test {

/// Runs `cmd` through /bin/sh; its exit status, or -1 if it did not exit normally.
inline int shell_status(const std::string& cmd) {
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace tessera::test
