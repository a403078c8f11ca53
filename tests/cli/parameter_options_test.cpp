// The render settings as `tessera render` options: registered from the table with the
// struct's defaults, parsed into the right fields, range-checked with one message naming
// option and value; README's usage block names exactly the options `render` has.
#include "cli/parameter_options.h"

#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli/option_checks.h"
#include "integrators/method.h"
#include "support/shell.h"

namespace tessera::cli {
namespace {

using tessera::test::CliResult;
using tessera::test::run_shell;
using tessera::test::run_tessera;

// The long options (--name) that start lines of `text`'s option list, as CLI11's help
// prints them ("  --tile UINT [3] ...", "  -h,--help ...").
std::set<std::string> help_options(const std::string& text) {
    std::set<std::string> names;
    const std::regex line(R"(^\s+(?:-\w,)?(--[a-z][a-z0-9-]*))");
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) {
        std::smatch m;
        if (std::regex_search(l, m, line)) names.insert(m[1]);
    }
    return names;
}

// Every --name in `text`.
std::set<std::string> named_options(const std::string& text) {
    std::set<std::string> names;
    const std::regex option(R"(--[a-z][a-z0-9-]*)");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), option); it != std::sregex_iterator(); ++it)
        names.insert(it->str());
    return names;
}

std::string read_readme() {
    std::ifstream in(std::string(TESSERA_SOURCE_DIR) + "/README.md");
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

TEST(ParameterOptions, HelpShowsTheStructDefaultsRangeAndUnit) {
    CLI::App app;
    RenderSettings s;
    add_parameter_options(app, s);
    const std::string help = app.help();
    std::istringstream in(help);
    std::vector<std::string> lines;
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    for (const Parameter& p : render_parameters()) {
        SCOPED_TRACE(p.option);
        const std::regex start("^\\s+" + std::string(p.option) + "\\b(?!-)");
        auto it = std::find_if(lines.begin(), lines.end(), [&](const std::string& l) { return std::regex_search(l, start); });
        ASSERT_NE(it, lines.end()) << help;
        if (*p.value_name) {
            // CLI11 prints "--tile UINT=3": the default it captured from the field.
            const std::string shown = "=" + default_text(p);
            const size_t at = it->find(shown);
            ASSERT_NE(at, std::string::npos) << *it;
            const size_t after = at + shown.size();
            EXPECT_TRUE(after == it->size() || (*it)[after] == ' ') << *it;
        }
        EXPECT_NE(help.find(parameter_help(p)), std::string::npos);
    }
    EXPECT_EQ(parameter_help(*find_parameter("--tile")), "igi: interleave tile edge n (n² sample sets); 1..8 px");
}

TEST(ParameterOptions, NoOptionsLeaveTheStructDefaults) {
    CLI::App app;
    RenderSettings s;
    add_parameter_options(app, s);
    app.parse("", false);
    const RenderSettings defaults;
    for (const Parameter& p : render_parameters())
        EXPECT_EQ(parameter_value(p, s), parameter_value(p, defaults)) << p.option;
}

// The viewer writes no checkpoint: `view --checkpoint-interval` is refused as unknown, not
// accepted and ignored; every other render setting is the viewer's too.
TEST(ParameterOptions, ViewerOptionsLeaveOutTheRenderOnlyOnes) {
    CLI::App app;
    RenderSettings s;
    add_parameter_options(app, s, true);
    EXPECT_THROW(app.parse("--checkpoint-interval 5", false), CLI::ExtrasError);
    size_t render_only = 0;
    for (const Parameter& p : render_parameters()) {
        EXPECT_EQ(app.get_option_no_throw(p.option) == nullptr, p.render_only) << p.option;
        render_only += p.render_only;
    }
    EXPECT_EQ(render_only, 1u);
}

TEST(ParameterOptions, OptionsSetTheirFields) {
    CLI::App app;
    RenderSettings s;
    add_parameter_options(app, s);
    app.parse("--tile 5 --no-filter --ic-error 0.5 --aov --ais-complete 7 --checkpoint-interval 0 --width 33 "
              "--ais-id-cov 1.5",
              false);
    EXPECT_EQ(s.igi.tile, 5u);
    EXPECT_FALSE(s.igi.filter);
    EXPECT_EQ(s.ic.error_bound, 0.5f);
    EXPECT_TRUE(s.aovs);
    EXPECT_EQ(s.igi.ais.complete_sets, 7);
    EXPECT_EQ(s.checkpoint_interval_s, 0.0);
    EXPECT_EQ(s.width, 33);
    EXPECT_EQ(s.igi.ais.id_cov, 1.5f);
    EXPECT_EQ(s.spp, RenderSettings{}.spp);
}

// Integers are decimal whatever their leading zeros: CLI11 alone reads "010" as octal 8
// and "08" as an error, while the range check reads them as 10 and 8.
TEST(ParameterOptions, LeadingZerosAreDecimal) {
    CLI::App app;
    RenderSettings s;
    add_parameter_options(app, s);
    app.parse("--spp 010 --seed 0017 --width 08 --tile 03", false);
    EXPECT_EQ(s.spp, 10u);
    EXPECT_EQ(s.seed, 17u);
    EXPECT_EQ(s.width, 8);
    EXPECT_EQ(s.igi.tile, 3u);
    // The viewer's own integer option (integer_in) alike.
    CLI::App view;
    int frame = -1;
    view.add_option("--screenshot-window-frame", frame)->transform(integer_in("--screenshot-window-frame", 0, 99));
    view.parse("--screenshot-window-frame 010", false);
    EXPECT_EQ(frame, 10);
}

// Out of range on the command line: exit 2, "tessera: error: <option> <value>: must be ...",
// before the scene is loaded (the scene here does not exist).
TEST(ParameterOptions, OutOfRangeValuesAreRejectedNamingOptionAndValue) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--tile 9", "--tile 9: must be in 1..8"},
        {"--spp 0", "--spp 0: must be in 1..1000000"},
        {"--ic-error 0", "--ic-error 0: must be in [0.001, 2]"},
        {"--width 20000", "--width 20000: must be in 1..16384"},
        {"--width 0", "--width 0: must be in 1..16384 (leave the option out for the scene camera's)"},
        {"--spp -1", "--spp -1: must be in 1..1000000"},
        {"--ais-complete 65", "--ais-complete 65: must be in 0..64"},
        {"--clamp -1", "--clamp -1: must be in [0, 1]"},
        {"--clamp 2", "--clamp 2: must be in [0, 1]"},
        {"--ais-ss-trigger 1.5", "--ais-ss-trigger 1.5: must be in [0, 1]"},
        {"--vpl-paths 70000", "--vpl-paths 70000: must be in 1..65536"},
    };
    for (const auto& [args, message] : cases) {
        const CliResult r = run_tessera("render does-not-exist.json --backend embree " + args);
        EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
        EXPECT_NE(r.output.find("tessera: error: " + message + "\n"), std::string::npos) << args << ": " << r.output;
    }
}

TEST(ParameterOptions, OptionsCommandPrintsTheMarkdownTable) {
    const CliResult r = run_tessera("options --markdown");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output, options_markdown());
    const CliResult plain = run_tessera("options");
    EXPECT_EQ(plain.exit_code, 0) << plain.output;
    for (const Parameter& p : render_parameters()) EXPECT_NE(plain.output.find(p.option), std::string::npos);
    // Aligned columns: "default" at one place on every line (--checkpoint-interval SECONDS,
    // the longest name, pushed it right).
    std::istringstream lines(plain.output);
    std::set<size_t> columns;
    for (std::string line; std::getline(lines, line);) columns.insert(line.find(" default "));
    EXPECT_EQ(columns.size(), 1u) << plain.output;
}

// README's usage block for `tessera render` names every option `render --help` lists, and
// no other.
TEST(ParameterOptions, ReadmeUsageNamesExactlyTheRenderOptions) {
    const std::string readme = read_readme();
    const size_t b = readme.find("build/tessera render [SCENE]");
    ASSERT_NE(b, std::string::npos) << "README.md: no usage line for `tessera render`";
    const size_t e = readme.find("build/tessera devices", b);
    ASSERT_NE(e, std::string::npos);
    const std::set<std::string> usage = named_options(readme.substr(b, e - b));

    const CliResult r = run_tessera("render --help");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    std::set<std::string> help = help_options(r.output);
    help.erase("--help");
    for (const Parameter& p : render_parameters()) EXPECT_TRUE(help.count(p.option)) << p.option;
    for (const std::string& o : help) EXPECT_TRUE(usage.count(o)) << "README's usage lacks " << o;
    for (const std::string& o : usage) EXPECT_TRUE(help.count(o)) << "README's usage names " << o << ", not an option";
    // --method's choices are the method table's rows, in its order, in the help and the usage.
    std::string choices;
    for (const MethodInfo& row : method_table()) choices += std::string(choices.empty() ? "" : "|") + row.name;
    EXPECT_NE(readme.find("[--method " + choices + "]", b), std::string::npos) << "README's usage: [--method " << choices << "]";
    EXPECT_NE(r.output.find("Rendering method: " + method_names()), std::string::npos) << r.output;
}

}  // namespace
}  // namespace tessera::cli
