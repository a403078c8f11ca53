#include "cli/option_checks.h"
#include "scene/loader.h"

#include <fcntl.h>
#include <unistd.h>

#include <cctype>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <map>
#include <set>
#include <system_error>

#include "device/effect_plan.h"
#include "image/atomic_file.h"
#include "image/fatal_signal_cleanup.h"
#include "util/error.h"
#include "util/input_limits.h"
#include "util/terminal_safe.h"

namespace tessera::cli {
namespace fs = std::filesystem;

CLI::Validator finite_number(const std::string& option) {
    return CLI::Validator([option](std::string& text) {
        double v = 0;
        const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
        if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size() || !std::isfinite(v))
            throw InputError(option + " " + (text.empty() ? "''" : text) + ": must be a finite number");
        return std::string();
    }, "");
}

CLI::Validator finite_number_in(const std::string& option, double lo, double hi, bool lo_open) {
    return CLI::Validator([=](std::string& text) {
        double v = 0;
        const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
        const bool number = !text.empty() && r.ec == std::errc() && r.ptr == text.data() + text.size();
        if (!number || !std::isfinite(v) || (lo_open ? !(v > lo) : !(v >= lo)) || !(v <= hi))
            throw InputError(option + " " + (text.empty() ? "''" : text) + ": must be a finite number " +
                             (lo_open ? "> " : ">= ") + limits::shown_limit(lo) + " and <= " + limits::shown_limit(hi));
        return std::string();
    }, "");
}

CLI::Validator integer_in(const std::string& option, long long lo, long long hi) {
    return CLI::Validator([=](std::string& text) {
        long long v = 0;
        const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
        if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size() || v < lo || v > hi)
            throw InputError(option + " " + (text.empty() ? "''" : text) + ": must be an integer in " +
                             std::to_string(lo) + ".." + std::to_string(hi));
        text = std::to_string(v);  // decimal, as CLI11 converts it: "010" is 10, not octal 8
        return std::string();
    }, "");
}

void reject_empty_values(const CLI::App& cmd) {
    for (const CLI::Option* o : cmd.get_options()) {
        if (o->count() == 0) continue;
        for (const std::string& v : o->results())
            if (v.empty()) {
                const std::string name = o->get_lnames().empty() ? o->get_name() : "--" + o->get_lnames()[0];
                throw InputError(name + " '': must not be empty");
            }
    }
}

void reject_options_as_values(const CLI::App& app, const std::vector<std::string>& args) {
    const CLI::App* cmd = nullptr;
    for (size_t i = 0; i < args.size(); ++i) {
        if (!cmd) {
            for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
                if (sub->get_name() == args[i]) cmd = sub;
            continue;
        }
        if (args[i] == "--") return;  // the rest are positionals
        if (args[i].rfind("--", 0) != 0 || args[i].find('=') != std::string::npos || i + 1 == args.size()) continue;
        const CLI::Option* o = cmd->get_option_no_throw(args[i]);
        const std::string& next = args[i + 1];
        if (o && o->get_expected_min() > 0 && next.rfind("--", 0) == 0 &&
            cmd->get_option_no_throw(next.substr(0, next.find('='))))
            throw InputError(args[i] + ": needs a value (the next word, " + next + ", is an option)");
    }
}

void require_exr_name(const std::string& option, const std::filesystem::path& path) {
    const std::string ext = path.extension().string(), name = path.filename().string();
    if (ext == ".exr") return;
    std::string lower = ext;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    std::error_code ec;
    const std::string example = "name the file, e.g. " + (path / "image.exr").string();
    const std::string why = lower == ".exr"                ? "must end in .exr (lower case)"
                            : name == ".exr"               ? "needs a file name before .exr"
                            : name.empty()                 ? "ends in '/'; " + example
                            : fs::is_directory(path, ec) ? "is a directory; " + example
                                                         : "must end in .exr";
    throw InputError(option + " " + path.string() + ": " + why);
}

fs::path default_output(const Scene& scene, const std::string& suffix) {
    const std::string stem = scene.source.empty() ? scene.name : scene.source.stem().string();
    return fs::path("out") / (stem + suffix);
}

void print_scene_notes(const std::vector<std::string>& notes) {
    for (const std::string& n : notes) std::fprintf(stderr, "tessera: note: %s\n", terminal_safe(n).c_str());
}

void check_data_dir(const std::string& data_dir) {
    if (data_dir.empty()) return;
    std::error_code ec;
    if (!fs::exists(data_dir, ec)) throw InputError("--data-dir " + data_dir + ": no such directory");
    if (!fs::is_directory(data_dir, ec)) throw InputError("--data-dir " + data_dir + ": not a directory");
}

namespace {

// The names the writer makes under `existing` (the nearest existing ancestor of `path`'s
// directory) must fit its file system's limit: each directory it creates, and the file's
// temporaries, whose names are up to kOutputNameExtra bytes longer (image/atomic_file.h).
// Else the render would run and fail at its first write.
void check_name_lengths(const std::string& name, const fs::path& path, const fs::path& existing) {
    const long name_max = ::pathconf(existing.empty() ? "." : existing.c_str(), _PC_NAME_MAX);
    const size_t limit = name_max > 0 ? size_t(name_max) : 255;
    const fs::path rest = path.lexically_relative(existing.empty() ? fs::path(".") : existing);
    for (auto it = rest.begin(); it != rest.end(); ++it) {
        const size_t n = it->string().size();
        if (std::next(it) == rest.end()) {
            if (n + kOutputNameExtra > limit)
                throw InputError(name + ": the file name is " + std::to_string(n) + " bytes; at most " +
                                 std::to_string(limit - kOutputNameExtra) + " here (it is written through "
                                 "temporaries whose names are up to " + std::to_string(kOutputNameExtra) +
                                 " bytes longer)");
        } else if (n > limit) {
            throw InputError(name + ": the directory name " + it->string().substr(0, 16) + "... is " +
                             std::to_string(n) + " bytes; at most " + std::to_string(limit) + " here");
        }
    }
}

void check_output(const OutputFile& o) {
    const std::string name = o.role + " " + o.path.string();
    const std::string file = o.path.filename().string();
    if (file.empty() || file == "." || file == "..") throw InputError(name + ": not a file name");
    std::error_code ec;
    const fs::file_status st = fs::status(o.path, ec);
    if (fs::is_directory(st)) throw InputError(name + ": is a directory");
    if (fs::exists(st) && !fs::is_regular_file(st)) throw InputError(name + ": not a regular file");
    // A link to a file not there yet is written through, as a shell's > would, but only
    // into a directory that exists: the run makes directories for its own paths, not for
    // where a link points (a link to /nonexistent/x made /nonexistent).
    if (!fs::exists(st) && fs::is_symlink(fs::symlink_status(o.path, ec))) {
        const fs::path target = output_target(o.path);
        if (fs::is_symlink(fs::symlink_status(target, ec)))
            throw InputError(name + ": is a symbolic link in a loop");
        const fs::path target_dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
        if (!fs::is_directory(target_dir, ec))
            throw InputError(name + ": is a symbolic link to " + target.string() + ", whose directory " +
                             target_dir.string() + " does not exist");
    }
    // The directory: the nearest existing ancestor must be a directory (the rest is made).
    const fs::path dir = existing_ancestor(o.path.parent_path());
    check_name_lengths(name, o.path, dir);
    // A link is written through: its target's name gets the temporaries.
    if (const fs::path target = output_target(o.path); target != o.path)
        check_name_lengths(name, target, existing_ancestor(target.parent_path()));
    const fs::file_status target = fs::status(dir, ec);  // through links
    if (!fs::exists(target) && fs::is_symlink(fs::symlink_status(dir, ec)))
        throw InputError(name + ": " + dir.string() + " is a symbolic link to nothing (a missing target or a loop)");
    if (fs::exists(target) && !fs::is_directory(target))
        throw InputError(name + ": " + dir.string() + " is not a directory");
}

}  // namespace

void check_outputs(const std::vector<OutputFile>& outputs, const std::vector<fs::path>& inputs) {
    // Keyed lookups, not pairs: a viewer script's --frame-images may name a million files.
    std::map<fs::path, size_t> in, seen;  // same_file key -> index (the first, for inputs)
    for (size_t k = 0; k < inputs.size(); ++k) in.emplace(same_file(inputs[k]), k);
    for (size_t i = 0; i < outputs.size(); ++i) {
        check_output(outputs[i]);
        const fs::path id = same_file(outputs[i].path);
        if (const auto k = in.find(id); k != in.end())
            throw InputError(outputs[i].role + " " + outputs[i].path.string() +
                             (k->second == 0 ? std::string(": is the scene file")
                                             : ": would replace an input of this run, " + inputs[k->second].string()));
        if (const auto j = seen.find(id); j != seen.end())
            throw InputError(outputs[i].role + " " + outputs[i].path.string() + ": is also " + outputs[j->second].role);
        seen.emplace(id, i);
    }
}

void check_output_directories(const std::vector<OutputFile>& outputs) {
    std::set<fs::path> done;
    for (const OutputFile& o : outputs) {
        // Where the writer puts it: a symbolic link's file (output_target).
        const fs::path target = output_target(o.path);
        const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
        if (!done.insert(dir).second) continue;
        const std::string name = o.role + " " + o.path.string();
        // The directory, or the nearest ancestor that exists, where the writer will make it
        // (check_outputs has made sure that one is a directory; where "/" or "." itself is
        // missing, the probe below says so).
        const fs::path existing = existing_ancestor(dir);
        const std::string missing = existing == dir ? "" : "cannot create the directory " + dir.string() + ": ";
        std::string probe = (existing / ".tessera-write-test.XXXXXX").string();
        const int fd = ::mkstemp(probe.data());
        if (fd < 0)
            throw RuntimeError(name + ": " + missing + "cannot write in " + existing.string() + ": " +
                               std::strerror(errno));
        const RemovedOnFatalSignal on_signal(probe);
        ::close(fd);
        ::unlink(probe.c_str());
    }
}

void check_scene_options(const RenderSettings& s, const std::string& components, const Scene& scene,
                         const fs::path& scene_path, bool switches_methods) {
    if (!igi_family(s.method) && !switches_methods) return;
    // Over the animation: a still renders frame 0's keys, a sequence every frame's.
    const EffectPlan plan = plan_effects_over_animation(scene);
    if (s.igi.march_steps == 0 && plan.medium)
        throw InputError("--march-steps 0: scene " + scene_path.string() +
                         " has a medium, whose light and transmittance " +
                         (igi_family(s.method) ? std::string("--method ") + method_name(s.method)
                                               : std::string("the igi family (the viewer's M key reaches it)")) +
                         " computes by a ray march; give at least 1 step");
    if (const std::string why = plan.idle_reason(s.igi.components); !why.empty())
        throw InputError("--components " + components + ": on scene " + scene_path.string() + ", " + why);
}

}  // namespace tessera::cli
