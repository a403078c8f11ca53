#include "cli/parameter_options.h"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <type_traits>

#include "cli/commands.h"

namespace tessera::cli {

std::string parameter_help(const Parameter& p) {
    if (*p.value_name == '\0') return p.doc;  // a flag
    std::string help = std::string(p.doc) + "; " + range_text(p);
    if (*p.unit) help += std::string(" ") + p.unit;
    return help;
}

void add_parameter_options(CLI::App& cmd, RenderSettings& settings, bool for_view) {
    for (const Parameter& p : render_parameters()) {
        if (for_view && p.render_only) continue;
        std::visit([&](auto get) {
            auto& field = get(settings);
            if constexpr (std::is_same_v<decltype(field), bool&>)
                cmd.add_flag((p.negated ? "!" : "") + std::string(p.option), field, parameter_help(p));
            else {
                CLI::Option* o = cmd.add_option(p.option, field, parameter_help(p));
                // Checked as text, before CLI11 converts it: CLI11 would read "-1" for an
                // unsigned as "Could not convert", "010" as octal, "" as 0, "inf" as inf.
                // A transform, not a check: CLI11 hands a check a copy, and the canonical
                // decimal text ("010" -> "10") must be what it converts.
                o->transform(CLI::Validator([&p](std::string& text) {
                    text = check_parameter_text(p, text);  // throws InputError naming option and value
                    return std::string();
                }, ""));
                if (p.zero_unset && field == 0)
                    o->default_str(default_text(p));
                else
                    o->capture_default_str();
            }
        }, p.field);
    }
}

void add_options_command(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("options", "List the render settings: option, default, range, unit");
    auto markdown = std::make_shared<bool>(false);
    cmd->add_flag("--markdown", *markdown, "Print README's options table (markdown)");
    cmd->callback([markdown] {
        if (*markdown) {
            std::fputs(options_markdown().c_str(), stdout);
            return;
        }
        // Columns as wide as their longest entry ("--checkpoint-interval SECONDS").
        int name_width = 0, default_width = 0;
        const auto name_of = [](const Parameter& p) {
            return *p.value_name ? std::string(p.option) + " " + p.value_name : std::string(p.option);
        };
        for (const Parameter& p : render_parameters()) {
            name_width = std::max(name_width, int(name_of(p).size()));
            default_width = std::max(default_width, int(default_text(p).size()));
        }
        for (const Parameter& p : render_parameters())
            std::printf("%-*s  default %-*s  %s\n", name_width, name_of(p).c_str(), default_width,
                        default_text(p).c_str(), parameter_help(p).c_str());
    });
}

}  // namespace tessera::cli
