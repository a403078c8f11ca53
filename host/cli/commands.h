// The `tessera` subcommands. Each registers itself on the CLI11 app and runs when its
// subcommand was given; errors propagate as InputError / RuntimeError to main().
#pragma once
#include <CLI/CLI.hpp>

namespace tessera::cli {

void add_render_command(CLI::App& app);
void add_devices_command(CLI::App& app);
void add_info_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_options_command(CLI::App& app);  // cli/parameter_options.cpp
void add_view_command(CLI::App& app);     // cli/view_command.cpp

}  // namespace tessera::cli
