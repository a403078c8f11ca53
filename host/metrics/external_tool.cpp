#include "metrics/external_tool.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <system_error>
#include <sstream>

#include "image/fatal_signal_cleanup.h"

extern char** environ;

namespace tessera::metrics {
namespace fs = std::filesystem;
namespace {

std::string read_text(const fs::path& p) {
    std::ifstream f(p);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

// A tool's captured stdout or stderr file, removed when the run is done.
struct OutputFile {
    explicit OutputFile(const std::string& p) : path(p), on_signal(path) {}
    ~OutputFile() {
        std::error_code ec;
        fs::remove(path, ec);
    }
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;
    fs::path path;
    RemovedOnFatalSignal on_signal;
};

}  // namespace

std::string env_or(const char* name, const std::string& fallback) {
    const char* v = std::getenv(name);
    return v && *v ? std::string(v) : fallback;
}

std::string last_line(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
    const auto nl = s.rfind('\n');
    return nl == std::string::npos ? s : s.substr(nl + 1);
}

ToolRun run_tool(const std::vector<std::string>& args) {
    ToolRun r;
    std::vector<std::string> words = args;
    std::vector<char*> argv;
    for (auto& a : words) argv.push_back(a.data());
    argv.push_back(nullptr);
    // Output to files rather than pipes: no deadlock on a tool that writes much to both.
    // The counter keeps two runs of one process (FLIP, then cvvdp) apart.
    static std::atomic<int> serial{0};
    std::error_code ec;
    const fs::path tmp_dir = fs::temp_directory_path(ec);
    if (ec) {  // the tool cannot run without its output files: said as a tool that did not start
        // The variable libstdc++ took it from (the first set of these), else its /tmp.
        std::string source = "/tmp";
        for (const char* var : {"TMPDIR", "TMP", "TEMP", "TEMPDIR"})
            if (const char* v = std::getenv(var); v && *v) {
                source = std::string(var) + "=" + v;
                break;
            }
        r.spawn_error = "no temporary directory: " + source + ": " + ec.message();
        return r;
    }
    const fs::path tmp = tmp_dir / ("tessera-tool-" + std::to_string(::getpid()) + "-" + std::to_string(serial++));
    const std::string out_path = tmp.string() + ".out", err_path = tmp.string() + ".err";
    // Removed on every return: a failed spawn has created them too (the file actions run
    // before the exec that fails). And by a signal that ends `compare` during a tool's run.
    const OutputFile out_file{out_path}, err_file{err_path};
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    // No terminal input: in a group of its own (below) a read from the terminal would stop it.
    posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_addopen(&fa, STDERR_FILENO, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    // In a process group of its own, which a signal that ends `compare` kills whole
    // (KilledOnFatalSignal): `kill PID` reaches compare alone, and the tool (Octave under
    // Python for HDR-VDP) would run on for minutes and write its map after compare went.
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGDEF);
    posix_spawnattr_setpgroup(&attr, 0);
    // The tool gets SIGPIPE's default back: main() ignores it, and an exec keeps ignored signals.
    sigset_t defaults;
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGPIPE);
    posix_spawnattr_setsigdefault(&attr, &defaults);
    pid_t pid = 0;
    std::optional<KilledOnFatalSignal> killed_on_signal;
    {
        const SignalsHeld registered;  // no signal between the spawn and the registration
        const int rc = posix_spawnp(&pid, argv[0], &fa, &attr, argv.data(), environ);
        posix_spawn_file_actions_destroy(&fa);
        posix_spawnattr_destroy(&attr);
        if (rc != 0) {
            r.spawn_error = std::strerror(rc);
            return r;
        }
        killed_on_signal.emplace(pid);
    }
    r.started = true;
    int status = 0;
    pid_t waited = 0;
    while ((waited = ::waitpid(pid, &status, 0)) < 0 && errno == EINTR) {
    }
    r.out = read_text(out_path);
    r.err = read_text(err_path);
    // A failed wait (SIGCHLD ignored: the child was not ours to wait for) has no status.
    r.exit_code = waited >= 0 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

std::string tool_failure(const std::string& python, const std::filesystem::path& script, const ToolRun& run) {
    if (!run.started) return "cannot run " + python + " (" + run.spawn_error + ")";
    if (run.exit_code == 127) return python + " not found";
    std::string why = last_line(run.err);
    return why.empty() ? script.filename().string() + " exited with status " + std::to_string(run.exit_code) : why;
}

}  // namespace tessera::metrics
