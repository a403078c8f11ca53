// The render-settings table: every declared range is enforced at its bounds with one
// message naming option and value, the defaults (RenderSettings' initializers) are valid
// and print exactly, and README.md's options table is the table's own rendering.
#include "render/parameters.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "util/error.h"

namespace tessera {
namespace {

// The InputError message validate_settings gives for `s`, "" when it accepts it.
std::string rejection(const RenderSettings& s) {
    try {
        validate_settings(s);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// Stores `v` into p's field, converted to the field's type.
void set_value(const Parameter& p, RenderSettings& s, double v) {
    std::visit([&](auto get) {
        auto& field = get(s);
        field = static_cast<std::remove_reference_t<decltype(field)>>(v);
    }, p.field);
}

bool is_real(const Parameter& p) {
    return std::holds_alternative<float& (*)(RenderSettings&)>(p.field) ||
           std::holds_alternative<double& (*)(RenderSettings&)>(p.field);
}

// The nearest value of p's field type beyond `bound` towards `direction` (an integer
// ±1; a float's or double's next representable value).
double beyond(const Parameter& p, double bound, double direction) {
    if (std::holds_alternative<float& (*)(RenderSettings&)>(p.field))
        return std::nextafter(static_cast<float>(bound), static_cast<float>(direction * INFINITY));
    if (std::holds_alternative<double& (*)(RenderSettings&)>(p.field)) return std::nextafter(bound, direction * INFINITY);
    return bound + direction;
}

TEST(Parameters, OptionsAreUniqueLongOptions) {
    std::set<std::string> seen;
    for (const Parameter& p : render_parameters()) {
        const std::string option = p.option;
        EXPECT_EQ(option.rfind("--", 0), 0u) << option;
        EXPECT_TRUE(seen.insert(option).second) << option << " declared twice";
        EXPECT_EQ(find_parameter(option), &p);
        EXPECT_EQ(is_flag(p), *p.value_name == '\0') << option << ": a flag has no value name, a value has one";
        EXPECT_NE(std::string(p.doc), "") << option;
        EXPECT_EQ(std::string(p.doc).find('|'), std::string::npos) << option << ": '|' breaks README's table";
    }
    EXPECT_EQ(find_parameter("--no-such-option"), nullptr);
}

TEST(Parameters, DefaultsAreValidAndPrintExactly) {
    const RenderSettings defaults;
    EXPECT_EQ(rejection(defaults), "");
    for (const Parameter& p : render_parameters()) {
        if (is_flag(p)) {
            EXPECT_EQ(default_text(p), "off");
            // The flag's absence is the struct's initializer: giving it changes the field.
            EXPECT_EQ(parameter_value(p, defaults), p.negated ? 1.0 : 0.0) << p.option;
            continue;
        }
        if (p.zero_unset) {  // 0: not given, the scene camera's
            EXPECT_EQ(default_text(p), "camera") << p.option;
            EXPECT_EQ(parameter_value(p, defaults), 0.0) << p.option;
            continue;
        }
        // The printed default reads back as the initializer, bit for bit, in the field's type.
        const std::string text = default_text(p);
        const bool is_float = std::holds_alternative<float& (*)(RenderSettings&)>(p.field);
        const double read = is_float ? double(std::stof(text)) : std::stod(text);
        EXPECT_EQ(read, parameter_value(p, defaults)) << p.option << " " << text;
    }
}

// Spot checks against the values the headers and README state.
TEST(Parameters, KnownDefaultsAndRanges) {
    auto check = [](const char* option, const char* def, const char* range) {
        const Parameter* p = find_parameter(option);
        ASSERT_NE(p, nullptr) << option;
        EXPECT_EQ(default_text(*p), def) << option;
        EXPECT_EQ(range_text(*p), range) << option;
    };
    check("--spp", "16", "1..1000000");
    check("--tile", "3", "1..8");
    check("--clamp", "0.1", "[0, 1]");
    check("--clamp-decay", "0.25", "[0, 1]");
    check("--ic-error", "0.3", "[0.001, 2]");
    check("--ais-id-cov", "2", "> 0");
    check("--checkpoint-interval", "120", ">= 0");
    check("--width", "camera", "1..16384");
    check("--no-filter", "off", "flag");
}

TEST(Parameters, EveryRangeHoldsAtItsBoundsAndRejectsBeyondNamingOptionAndValue) {
    for (const Parameter& p : render_parameters()) {
        if (is_flag(p)) continue;
        SCOPED_TRACE(p.option);
        const std::string range = range_text(p);
        const std::string must = range[0] == '>' ? ": must be " + range : ": must be in " + range;
        RenderSettings s;
        if (!p.min_exclusive) {
            set_value(p, s, p.min);
            EXPECT_EQ(rejection(s), "");
        }
        if (std::isfinite(p.max)) {
            set_value(p, s, p.max);
            EXPECT_EQ(rejection(s), "");
            s = RenderSettings{};
            set_value(p, s, beyond(p, p.max, +1));
            const std::string m = rejection(s);
            EXPECT_EQ(m.rfind(std::string(p.option) + " ", 0), 0u) << m;
            EXPECT_NE(m.find(must), std::string::npos) << m;
        }
        // Below the minimum, where the field's type can hold it.
        const bool unsigned_field = std::holds_alternative<uint32_t& (*)(RenderSettings&)>(p.field);
        if (p.min_exclusive || !(unsigned_field && p.min == 0)) {
            s = RenderSettings{};
            // A zero_unset field's 0 means "not given" and is valid: -1 is the first value below.
            set_value(p, s, p.min_exclusive ? p.min : p.zero_unset ? -1 : beyond(p, p.min, -1));
            const std::string m = rejection(s);
            EXPECT_EQ(m.rfind(std::string(p.option) + " ", 0), 0u) << m;
            EXPECT_NE(m.find(must), std::string::npos) << m;
        }
        if (is_real(p)) {  // NaN compares false with every bound
            s = RenderSettings{};
            set_value(p, s, std::numeric_limits<double>::quiet_NaN());
            EXPECT_NE(rejection(s), "");
        }
    }
}

// The message check_parameter_text gives for `text`, "" when it accepts it.
std::string text_rejection(const char* option, const std::string& text) {
    try {
        check_parameter_text(*find_parameter(option), text);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// Command-line text: one message form for every bad value, before CLI11 converts it.
TEST(Parameters, CommandLineTextIsCheckedBeforeConversion) {
    EXPECT_EQ(text_rejection("--spp", "-1"), "--spp -1: must be in 1..1000000");
    EXPECT_EQ(text_rejection("--spp", ""), "--spp '': must be an integer in 1..1000000");
    EXPECT_EQ(text_rejection("--spp", "1.5"), "--spp 1.5: must be an integer in 1..1000000");
    EXPECT_EQ(text_rejection("--spp", "0x10"), "--spp 0x10: must be an integer in 1..1000000");
    EXPECT_EQ(text_rejection("--spp", " 4"), "--spp  4: must be an integer in 1..1000000");
    EXPECT_EQ(text_rejection("--width", "0"),
              "--width 0: must be in 1..16384 (leave the option out for the scene camera's)");
    EXPECT_EQ(text_rejection("--seed", "-1"), "--seed -1: must be in 0..4294967295");
    EXPECT_EQ(text_rejection("--seed", "99999999999"), "--seed 99999999999: must be in 0..4294967295");
    EXPECT_EQ(text_rejection("--clamp", "inf"), "--clamp inf: must be a finite number in [0, 1]");
    EXPECT_EQ(text_rejection("--clamp", "nan"), "--clamp nan: must be a finite number in [0, 1]");
    EXPECT_EQ(text_rejection("--clamp", "1e400"), "--clamp 1e400: must be a finite number in [0, 1]");
    // Above 1 every VPL is clamped already; 1e30 made b = 1/(c·D)² underflow to 0.
    EXPECT_EQ(text_rejection("--clamp", "1e30"), "--clamp 1e30: must be in [0, 1]");
    EXPECT_EQ(text_rejection("--clamp", "1"), "");
    EXPECT_EQ(text_rejection("--ic-error", "0.5x"), "--ic-error 0.5x: must be a number in [0.001, 2]");
    EXPECT_EQ(text_rejection("--checkpoint-interval", "-0.5"), "--checkpoint-interval -0.5: must be >= 0");
    EXPECT_EQ(text_rejection("--spp", "1000000"), "");
    EXPECT_EQ(text_rejection("--clamp", "0"), "");
    // Integers are passed on in canonical decimal: CLI11 would read "010" as octal 8.
    EXPECT_EQ(check_parameter_text(*find_parameter("--spp"), "010"), "10");
    EXPECT_EQ(check_parameter_text(*find_parameter("--ic-error"), "0.25"), "0.25");
}

TEST(Parameters, MessagesNameOptionValueAndRange) {
    RenderSettings s;
    s.igi.tile = 9;
    EXPECT_EQ(rejection(s), "--tile 9: must be in 1..8");
    s = {};
    s.spp = 0;
    EXPECT_EQ(rejection(s), "--spp 0: must be in 1..1000000");
    s = {};
    s.width = -1;
    EXPECT_EQ(rejection(s), "--width -1: must be in 1..16384");
    s = {};
    s.width = 0;  // not given: the camera's
    EXPECT_EQ(rejection(s), "");
    s = {};
    s.ic.error_bound = 2.5f;
    EXPECT_EQ(rejection(s), "--ic-error 2.5: must be in [0.001, 2]");
    s = {};
    s.igi.clamp_c = -0.5f;
    EXPECT_EQ(rejection(s), "--clamp -0.5: must be in [0, 1]");
    s = {};
    s.checkpoint_interval_s = -1;
    EXPECT_EQ(rejection(s), "--checkpoint-interval -1: must be >= 0");
    s = {};
    s.igi.ais.id_cov = 0;
    EXPECT_EQ(rejection(s), "--ais-id-cov 0: must be > 0");
    s = {};
    s.igi.ais.complete_sets = 65;
    EXPECT_EQ(rejection(s), "--ais-complete 65: must be in 0..64");
    // The first parameter out of range in table order is the one named.
    s = {};
    s.spp = 0;
    s.igi.tile = 0;
    EXPECT_EQ(rejection(s), "--spp 0: must be in 1..1000000");
}

// README.md's options table is options_markdown() verbatim, between its markers.
// Each parameter's scope (the methods that read it, behind render's "is ignored" note)
// agrees with the prefix its doc line gives users, and decides by method as it says.
TEST(Parameters, ScopeMatchesTheDocPrefix) {
    for (const Parameter& p : render_parameters()) {
        SCOPED_TRACE(p.option);
        const std::string doc = p.doc;
        ParameterScope expected = ParameterScope::All;
        if (doc.rfind("pt:", 0) == 0) expected = ParameterScope::Pt;
        else if (doc.rfind("ais:", 0) == 0) expected = ParameterScope::Ais;
        else if (doc.rfind("ic/tic:", 0) == 0) expected = ParameterScope::Ic;
        else if (doc.rfind("igi", 0) == 0) expected = ParameterScope::IgiFamily;
        EXPECT_EQ(p.scope, expected) << doc;
    }
    const Parameter& tile = *find_parameter("--tile");
    EXPECT_FALSE(parameter_applies(tile, Method::Direct));
    EXPECT_FALSE(parameter_applies(tile, Method::PathTrace));
    for (Method m : {Method::Igi, Method::Ais, Method::AisMax, Method::Ic, Method::Tic})
        EXPECT_TRUE(parameter_applies(tile, m));
    EXPECT_TRUE(parameter_applies(*find_parameter("--max-depth"), Method::PathTrace));
    EXPECT_FALSE(parameter_applies(*find_parameter("--max-depth"), Method::Igi));
    EXPECT_TRUE(parameter_applies(*find_parameter("--ais-edge-samples"), Method::AisMax));
    EXPECT_FALSE(parameter_applies(*find_parameter("--ais-edge-samples"), Method::Igi));
    EXPECT_TRUE(parameter_applies(*find_parameter("--ic-paths"), Method::Tic));
    EXPECT_FALSE(parameter_applies(*find_parameter("--ic-paths"), Method::Ais));
    EXPECT_TRUE(parameter_applies(*find_parameter("--spp"), Method::Direct));
}

TEST(Parameters, ReadmeTableMatchesTheDeclarations) {
    std::ifstream in(std::string(TESSERA_SOURCE_DIR) + "/README.md");
    ASSERT_TRUE(in) << "README.md not found";
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string readme = ss.str();
    const std::string begin = "<!-- options-table:begin (scripts/options-table --write) -->\n";
    const std::string end = "<!-- options-table:end -->";
    const size_t b = readme.find(begin);
    ASSERT_NE(b, std::string::npos) << "README.md lacks the line " << begin;
    const size_t e = readme.find(end, b);
    ASSERT_NE(e, std::string::npos) << "README.md lacks the line " << end;
    EXPECT_EQ(readme.substr(b + begin.size(), e - b - begin.size()), options_markdown())
        << "README's options table differs from host/render/parameters.cpp: run scripts/options-table --write";
}

}  // namespace
}  // namespace tessera
