// tessera: command-line entry point. Every failure ends as one line on stderr,
// "tessera: error: ...", and a non-zero exit: 2 for bad input, 1 for runtime failures.
// A render stopped by SIGINT/SIGTERM (after saving a checkpoint) exits with 130.
#include <cstdio>
#include <exception>
#include <unistd.h>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "util/error.h"

int main(int argc, char** argv) {
    CLI::App app{"Tessera: interactive global illumination on OpenCL devices and Embree"};
    app.require_subcommand(1);
    tessera::cli::add_render_command(app);
    tessera::cli::add_devices_command(app);
    tessera::cli::add_info_command(app);
    tessera::cli::add_compare_command(app);
    tessera::cli::add_options_command(app);
    tessera::cli::add_view_command(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "tessera: error: %s (see --help)\n", e.what());
        return e.get_exit_code() ? e.get_exit_code() : 2;
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
