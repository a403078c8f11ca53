// The render settings of render/parameters.h as CLI11 options of `tessera render`, and
// the `tessera options` command that prints them (README's table comes from it).
#pragma once
#include <CLI/CLI.hpp>

#include <string>

#include "render/parameters.h"

namespace tessera::cli {

/// Registers one option per render_parameters() entry on `cmd`, storing into `settings`
/// (which must outlive `cmd`'s parse). Help shows the doc, range and unit and the default
/// (the field's value in `settings` at registration). Each given value is checked as text
/// by check_parameter_text while parsing (InputError naming option and value, thrown out
/// of CLI::App::parse); validate_settings still runs after parsing (render_frame runs it too).
/// `for_view`: the viewer's options, without those it does not read (Parameter::render_only),
/// so that giving one is refused as an unknown option.
void add_parameter_options(CLI::App& cmd, RenderSettings& settings, bool for_view = false);

/// The option's help line: "igi: light paths per sample set; 1..65536 paths".
std::string parameter_help(const Parameter& p);

}  // namespace tessera::cli
