// tessera: command-line entry point. Every failure ends as one line on stderr,
// "tessera: error: ...", and a non-zero exit: 2 for bad input, 1 for runtime failures.
// A render stopped by SIGINT/SIGTERM (after saving a checkpoint) exits with 130. In a
// distributed render (mpirun) only rank 0 prints, naming the rank that failed.
#include <cstdio>
#include <exception>
#include <unistd.h>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "render/cluster.h"
#include "util/error.h"

int main(int argc, char** argv) {
    CLI::App app{"Tessera: interactive global illumination on OpenCL devices and Embree"};
    app.require_subcommand(1);
    tessera::cli::add_render_command(app);
    tessera::cli::add_devices_command(app);
    tessera::cli::add_info_command(app);
    tessera::cli::add_compare_command(app);
    tessera::cli::add_options_command(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "tessera: error: %s (see --help)\n", e.what());
        return e.get_exit_code() ? e.get_exit_code() : 2;
    } catch (const tessera::RankFailure& e) {
        // A distributed render (render/cluster.h): rank 0 gives the one message, naming the
        // rank that failed; the other ranks exit with the same status and say nothing.
        if (!e.silent())
            std::fprintf(stderr, "tessera: %s%s\n", e.exit_code == 130 ? "" : "error: ", e.what());
        return e.exit_code;
    } catch (const tessera::Interrupted& e) {
        std::fprintf(stderr, "%stessera: %s\n", ::isatty(STDERR_FILENO) ? "\n" : "", e.what());
        return 130;
    } catch (const tessera::InputError& e) {
        std::fprintf(stderr, "tessera: error: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tessera: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
