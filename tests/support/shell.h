// Running a shell command or the tessera executable from a test (the CLI tests and the
// bench scripts, which are Python, driven end to end).
#pragma once
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace tessera::test {

/// Runs `cmd` through /bin/sh; its exit status, or -1 if it did not exit normally.
inline int shell_status(const std::string& cmd) {
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// 1 when `python` (an interpreter's command, default python3) imports every module of
/// `modules` ("numpy, matplotlib": a Python import list); for tests that skip without the
/// optional Python tools of bench/requirements.txt.
inline bool python_imports(const std::string& modules, const std::string& python = "python3") {
    return shell_status(python + " -c 'import " + modules + "' > /dev/null 2>&1") == 0;
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

/// Runs `words` (words[0] an absolute path; no shell), stdout and stderr into one pipe,
/// in a process group of its own when `own_group`. Each time output arrives, calls
/// `on_output(pid, output so far)`: a test sends its signal from there once a text has
/// appeared (an interrupted render, a rank of an MPI job).
template <class OnOutput>
CliResult run_watched(std::vector<std::string> words, bool own_group, OnOutput on_output) {
    std::vector<char*> argv;  // built before fork: no malloc in the child
    for (auto& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    int fds[2];
    if (::pipe(fds) != 0) return {-2, "pipe failed"};
    const pid_t pid = ::fork();
    if (pid == 0) {
        if (own_group) ::setpgid(0, 0);
        ::dup2(fds[1], STDOUT_FILENO);
        ::dup2(fds[1], STDERR_FILENO);
        ::close(fds[0]);
        ::close(fds[1]);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    ::close(fds[1]);
    std::string out;
    std::array<char, 4096> buf;
    while (true) {
        const ssize_t n = ::read(fds[0], buf.data(), buf.size());
        if (n <= 0) break;
        out.append(buf.data(), size_t(n));
        on_output(pid, out);
    }
    ::close(fds[0]);
    int status = 0;
    ::waitpid(pid, &status, 0);
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
