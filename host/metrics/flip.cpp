#include "metrics/flip.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

extern char** environ;

namespace tessera::metrics {
namespace fs = std::filesystem;
namespace {

std::string env_or(const char* name, const std::string& fallback) {
    const char* v = std::getenv(name);
    return v && *v ? std::string(v) : fallback;
}

std::string read_text(const fs::path& p) {
    std::ifstream f(p);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

std::string last_line(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
    const auto nl = s.rfind('\n');
    return nl == std::string::npos ? s : s.substr(nl + 1);
}

}  // namespace

FlipResult compute_flip(const fs::path& ref, const fs::path& test, const std::optional<fs::path>& map_png) {
    FlipResult r;
    const std::string python = env_or("TESSERA_PYTHON", "python3");
    const fs::path script = env_or("TESSERA_FLIP_SCRIPT", std::string(TESSERA_SOURCE_DIR) + "/bench/flip_metric.py");
    if (!fs::exists(script)) {
        r.reason = "script " + script.string() + " not found";
        return r;
    }
    // posix_spawn with an argument vector rather than popen: no shell, so paths need no quoting.
    std::vector<std::string> args = {python, script.string(), ref.string(), test.string()};
    if (map_png) args.insert(args.end(), {"--map", map_png->string()});
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);

    const fs::path tmp = fs::temp_directory_path() / ("tessera-flip-" + std::to_string(::getpid()));
    const std::string out_path = tmp.string() + ".out", err_path = tmp.string() + ".err";
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_addopen(&fa, STDERR_FILENO, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    pid_t pid = 0;
    const int rc = posix_spawnp(&pid, python.c_str(), &fa, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) {
        r.reason = "cannot run " + python + " (" + std::string(std::strerror(rc)) + ")";
        return r;
    }
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    const std::string out = read_text(out_path), err = read_text(err_path);
    std::error_code ec;
    fs::remove(out_path, ec);
    fs::remove(err_path, ec);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        r.reason = (code == 127 ? python + " not found" : last_line(err));
        if (r.reason.empty()) r.reason = script.filename().string() + " exited with status " + std::to_string(code);
        return r;
    }
    try {
        const auto j = nlohmann::json::parse(out);
        r.mean = j.at("mean").get<double>();
        r.pct_gt_0_1 = j.at("p_gt_0_1").get<double>();
        r.pct_gt_0_3 = j.at("p_gt_0_3").get<double>();
        r.implementation = j.value("implementation", "flip-evaluator");
        r.available = true;
    } catch (const std::exception& e) {
        r.reason = "unparsable output from " + script.filename().string() + ": " + e.what();
    }
    return r;
}

}  // namespace tessera::metrics
