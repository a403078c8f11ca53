// The render settings a user sets, declared once: option name, the RenderSettings field it
// sets, valid range, unit and a one-line doc. The default is the field's initializer in
// RenderSettings (and the structs it holds), read from a default-constructed RenderSettings.
// From this table: the `tessera render` options (cli/parameter_options.h), the range check
// that render_frame and the CLI both run (validate_settings), and README's options table
// (options_markdown; a test keeps README in step). To add a setting: one entry here.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <variant>

#include "render/settings.h"

namespace tessera {

/// Where a parameter's value lives in RenderSettings: a function returning a reference to
/// the field (a captureless lambda; members of the nested settings structs cannot be named
/// by a pointer-to-member). The field's type selects the alternative.
using ParameterField = std::variant<uint32_t& (*)(RenderSettings&), int& (*)(RenderSettings&),
                                    float& (*)(RenderSettings&), double& (*)(RenderSettings&),
                                    bool& (*)(RenderSettings&)>;

/// The methods that read a parameter (the prefix of its doc line says the same in words).
enum class ParameterScope {
    All,        ///< every method
    Pt,         ///< pt
    IgiFamily,  ///< igi, ais, ais-max, ic, tic (not direct, not pt)
    Ais,        ///< ais, ais-max
    Ic,         ///< ic, tic
};

/// One user-settable render setting. A bool field is a flag: giving the option sets the
/// field to !negated.
struct Parameter {
    const char* option;          ///< the long option, e.g. "--tile"
    const char* value_name;      ///< placeholder in usage lines, e.g. "N" ("" for a flag)
    ParameterField field;
    double min = 0;              ///< valid range [min, max] (min excluded when min_exclusive)
    double max = 0;              ///< +inf: no bound but the field type's
    bool min_exclusive = false;  ///< (min, max]: e.g. a divisor that must be > 0
    bool negated = false;        ///< flags: the option clears the field (--no-filter)
    bool zero_unset = false;     ///< the field's 0 means "option not given" (the camera's size);
                                 ///< a value given on the command line must be in [min, max]
    const char* unit = "";       ///< e.g. "px", "s"; "" for a plain count or ratio
    const char* doc = "";        ///< one line; "method: ..." when only some methods read it
    ParameterScope scope = ParameterScope::All;  ///< the methods that read it
    bool render_only = false;    ///< `tessera render` reads it and `view` has no such option
};

/// Every parameter, in the order of `tessera render --help` and README's table.
std::span<const Parameter> render_parameters();

/// Whether p's field is a bool (a flag: the option takes no value).
bool is_flag(const Parameter& p);

/// Whether p's field is an integer (uint32_t or int).
bool is_integer(const Parameter& p);

/// Whether `method` reads p (p.scope).
bool parameter_applies(const Parameter& p, Method method);

/// The methods of p.scope in words, e.g. "igi, ais, ais-max, ic and tic".
const char* parameter_scope_text(const Parameter& p);

/// The parameter named `option` ("--tile"); nullptr when none is.
const Parameter* find_parameter(const std::string& option);

/// The field's value in `s`, widened to double (flags: 0 or 1).
double parameter_value(const Parameter& p, const RenderSettings& s);

/// Throws InputError "--tile 9: must be in 1..8" (option, value, range) when p's field in
/// `s` is out of p's range (NaN included). Flags are always valid; 0 is valid for a
/// zero_unset parameter (not given).
void validate_parameter(const Parameter& p, const RenderSettings& s);

/// Checks the text given for p on the command line before it is converted: a decimal
/// number (an integer for integer fields), finite, in p's range and in the field type's
/// (0 not allowed for a zero_unset parameter). Returns the text to convert (integers
/// canonical decimal: "010" is 10, not octal). Throws InputError naming option and value:
/// "--spp -1: must be in 1..1000000", "--clamp inf: must be a finite number >= 0",
/// "--spp '': must be in 1..1000000".
std::string check_parameter_text(const Parameter& p, const std::string& text);

/// validate_parameter for every parameter, in table order: the check render_frame runs on
/// its settings and the CLI runs before loading the scene.
void validate_settings(const RenderSettings& s);

/// Valid range as README and the messages print it: "1..8" (integers; with no upper
/// bound the field type's, "0..4294967295"), "[0.001, 2]" (reals), ">= 0" / "> 0" (reals
/// with no upper bound), "flag" for a flag.
std::string range_text(const Parameter& p);

/// The default, from RenderSettings{}: "3", "0.05", "120"; "off" for a flag; "camera"
/// for a zero_unset parameter (the scene camera's value).
std::string default_text(const Parameter& p);

/// The options table of README.md (markdown, one row per parameter, header included).
std::string options_markdown();

}  // namespace tessera
