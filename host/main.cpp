// tessera: command-line entry point. Every failure ends as one line on stderr,
// "tessera: error: ...", and a non-zero exit: 2 for bad input, 1 for runtime failures.
// A render stopped by SIGINT/SIGTERM (after saving a checkpoint) exits with 130. In a
// distributed render (mpirun) only rank 0 prints, naming the rank that failed.
#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <regex>
#include <sstream>
#include <string>
#include <vector>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "cli/option_checks.h"
#include "render/cluster.h"
#include "render/interrupt.h"
#include "scene/json_field.h"
#include "util/error.h"
#include "util/heap.h"
#include "util/terminal_safe.h"

namespace {

// Prints `message` the way main() reports failures and returns `code`. In an MPI job whose
// render has not reached its first collective step (a bad option fails while parsing),
// the other ranks wait in that step: this rank joins it, and only rank 0 prints, once for
// all ranks (render/cluster.h).
int fail(const std::string& message, int code) {
    auto print = [](const std::string& text, int status) {
        std::fprintf(stderr, "%stessera: %s%s\n", status == 130 && ::isatty(STDERR_FILENO) ? "\n" : "",
                     status == 130 ? "" : "error: ", tessera::terminal_safe(text).c_str());
        return status;
    };
    if (tessera::launched_by_mpi() && !tessera::world_cluster().stepped()) {
        try {
            tessera::world_cluster().step([&] { throw tessera::RankFailure(message, code); });
        } catch (const tessera::RankFailure& f) {
            return f.silent() ? f.exit_code : print(f.what(), f.exit_code);
        }
    }
    return print(message, code);
}

// CLI11's message for an option given more times than it takes, "<option>: At Most 1
// required but received <n>", in the words of the problem; any other message as it is.
std::string parse_message(const std::string& what) {
    static const std::regex twice("^(-[^:]*): At Most 1 required but received ([0-9]+)$");
    std::smatch m;
    if (!std::regex_match(what, m, twice)) return what;
    return m[1].str() + ": given " + m[2].str() + " times; give it once";
}

// CLI11's "The following argument(s) was/were not expected: --sppp" with, for each
// misspelt long option, the closest one the command has ("--sppp: did you mean --spp?"),
// as scene files' unknown keys get (scene/json_field.h).
std::string with_suggestions(CLI::App& app, const std::string& what) {
    std::vector<std::string> names;
    for (const CLI::App* sub : app.get_subcommands())
        for (const CLI::Option* opt : sub->get_options())
            for (const std::string& n : opt->get_lnames()) names.push_back(n);
    const std::vector<std::string_view> known(names.begin(), names.end());
    // Which other commands take a name exactly ("compare ... --spp": render's, view's).
    const auto commands_taking = [&app](const std::string& name) {
        std::string commands;
        for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
            if (!sub->parsed())
                for (const CLI::Option* opt : sub->get_options())
                    for (const std::string& n : opt->get_lnames())
                        if (n == name) commands += (commands.empty() ? "" : ", ") + sub->get_name();
        return commands;
    };
    std::string suggestions;
    const size_t colon = what.find(": ");
    std::istringstream words(colon == std::string::npos ? "" : what.substr(colon + 2));
    for (std::string word; words >> word;) {
        if (word.rfind("--", 0) != 0) continue;
        // Names without their "--": it would make any two look alike ("--bogus", "--out").
        // At most one edit in three letters: "spp" is not a typo of "map".
        const std::string name = word.substr(0, word.find('=')), bare = name.substr(2);
        if (const std::string others = commands_taking(bare); !others.empty())
            suggestions += "; " + name + " is an option of tessera " + others;
        else if (const std::string best = tessera::scene_detail::closest_match(bare, known, std::max<size_t>(1, bare.size() / 3));
                 !best.empty())
            suggestions += "; " + name + ": did you mean --" + best + "?";
    }
    return what + suggestions;
}

// "unknown command 'rnder'; the commands are render, devices, ..." when the first
// argument is not an option and names no subcommand ("" when it does): CLI11 says only
// that a subcommand is required.
std::string unknown_command(CLI::App& app, int argc, char** argv) {
    if (argc < 2 || argv[1][0] == '-') return "";
    std::string names;
    for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
        if (sub->get_name() == argv[1]) return "";
        names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    return std::string("unknown command '") + argv[1] + "'; the commands are " + names;
}

// Whether stdout's reader has left: a pipe or socket whose other end is closed (poll says
// POLLERR). glibc drops a stream's buffer at a failed write, so a later fflush has nothing
// to write and leaves errno 0: EPIPE is then asked of the descriptor.
bool stdout_reader_left() {
    struct stat st {};
    if (::fstat(STDOUT_FILENO, &st) != 0 || !(S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode))) return false;
    pollfd p{STDOUT_FILENO, POLLOUT, 0};
    return ::poll(&p, 1, 0) == 1 && (p.revents & (POLLERR | POLLHUP)) != 0;
}

// Whether what the command printed on stdout (the files it wrote, compare's metrics, info)
// reached it: a full disk or a closed stdout failed silently with exit 0. A reader that
// left (`| head`, EPIPE) is not a failure: the work is done, as with `cmd | head` in a shell.
// Printed here, by the rank whose stdout failed, not through fail(): the work is done, and
// under mpirun fail() would join a collective step the other ranks, finished, never reach.
int check_stdout(int status) {
    errno = 0;
    const bool flushed = std::fflush(stdout) == 0;
    if (flushed && !std::ferror(stdout)) return status;
    const int err = errno;
    if (status != 0 || err == EPIPE || (err == 0 && stdout_reader_left())) return status;
    std::fprintf(stderr, "tessera: error: cannot write to standard output%s%s\n", err ? ": " : "",
                 err ? std::strerror(err) : "");
    return 1;
}

// The command line's work: parse, run the subcommand, report failures; the exit status.
int run(int argc, char** argv) {
    tessera::keep_frame_memory();
    CLI::App app{"Tessera: interactive global illumination on OpenCL devices and Embree"};
    app.require_subcommand(1);
    tessera::cli::add_render_command(app);
    tessera::cli::add_devices_command(app);
    tessera::cli::add_info_command(app);
    tessera::cli::add_compare_command(app);
    tessera::cli::add_options_command(app);
    tessera::cli::add_view_command(app);
    if (const std::string bad = unknown_command(app, argc, argv); !bad.empty()) return fail(bad + " (see --help)", 2);
    try {
        tessera::cli::reject_options_as_values(app, std::vector<std::string>(argv + 1, argv + argc));
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ArgumentMismatch& e) {
        // An option given twice: CLI11 says "--spp: At Most 1 required but received 2".
        return fail(parse_message(e.what()) + " (see --help)", 2);
    } catch (const CLI::ExtrasError& e) {
        return fail(with_suggestions(app, e.what()) + " (see --help)", 2);
    } catch (const CLI::ParseError& e) {
        // CLI11's own codes (105-120) would say nothing a script can use: every parse error
        // is bad input, exit 2 as docs/input-limits.md says. A "success" (help) exits 0.
        if (e.get_exit_code() == 0) return app.exit(e);
        return fail(std::string(e.what()) + " (see --help)", 2);
    } catch (const tessera::RankFailure& e) {
        // A distributed render (render/cluster.h): rank 0 gives the one message, naming the
        // rank that failed; the other ranks exit with the same status and say nothing.
        if (!e.silent())
            std::fprintf(stderr, "tessera: %s%s\n", e.exit_code == 130 ? "" : "error: ",
                         tessera::terminal_safe(e.what()).c_str());
        return e.exit_code;
    } catch (const tessera::Interrupted& e) {
        return fail(e.what(), 130);
    } catch (const tessera::InputError& e) {
        return fail(e.what(), 2);
    } catch (const tessera::BuildError& e) {
        // PoCL's LLVM puts its own SIGINT/SIGTERM handlers in front of ours while it
        // compiles; they delete its temporary files and pass the signal on, so a Ctrl-C
        // during a kernel build fails the build. That is the interrupt, for every command.
        if (tessera::interrupt_signal())
            return fail("interrupted during an OpenCL kernel build (it stopped the build); no checkpoint written", 130);
        return fail(e.what(), 1);
    } catch (const std::exception& e) {
        return fail(e.what(), 1);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    // A closed pipe on stdout or stderr is EPIPE on the write, not SIGPIPE's death mid-pass
    // (no checkpoint, the frame's temporaries left): progress lines are then lost, the
    // render goes on, and check_stdout decides.
    std::signal(SIGPIPE, SIG_IGN);
    return check_stdout(run(argc, argv));
}
