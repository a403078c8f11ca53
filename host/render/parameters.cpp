#include "render/parameters.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

#include "integrators/method.h"
#include "util/error.h"

namespace tessera {
namespace {

constexpr double kNoMax = std::numeric_limits<double>::infinity();

// The field `path` of RenderSettings (e.g. igi.tile) as a ParameterField.
#define TS_SETTING(path) +[](RenderSettings& s) -> auto& { return s.path; }

// Ranges: those render_frame has always enforced, plus bounds where a value outside makes
// no sense (AIS triggers compare with guidance in [0, 1]; --ais-id-cov divides).
const Parameter kParameters[] = {
    {.option = "--spp", .value_name = "N", .field = TS_SETTING(spp), .min = 1, .max = 1000000,
     .unit = "passes", .doc = "Samples (passes) per pixel, one camera sample per pixel each"},
    {.option = "--shadow-samples", .value_name = "N", .field = TS_SETTING(shadow_samples), .min = 1, .max = 4096,
     .unit = "samples", .doc = "Area-light samples per camera hit and pass"},
    {.option = "--width", .value_name = "W", .field = TS_SETTING(width), .min = 1, .max = 16384,
     .zero_unset = true, .unit = "px",
     .doc = "Image width; not given: the scene camera's, or with --height alone scaled to the camera's aspect ratio"},
    {.option = "--height", .value_name = "H", .field = TS_SETTING(height), .min = 1, .max = 16384,
     .zero_unset = true, .unit = "px",
     .doc = "Image height; not given: the scene camera's, or with --width alone scaled to the camera's aspect ratio"},
    {.option = "--seed", .value_name = "S", .field = TS_SETTING(seed), .min = 0, .max = kNoMax,
     .doc = "Random seed (samples are counter-based per seed, pixel and pass)"},
    {.option = "--aov", .value_name = "", .field = TS_SETTING(aovs),
     .doc = "Also write albedo, normal and depth channels (igi family: also per-component channels)"},
    {.option = "--checkpoint-interval", .value_name = "SECONDS", .field = TS_SETTING(checkpoint_interval_s),
     .min = 0, .max = kNoMax, .unit = "s",
     .doc = "Seconds between checkpoints (0: only when interrupted by SIGINT, SIGTERM or SIGHUP)",
     .render_only = true},  // the viewer writes no checkpoint
    {.option = "--max-depth", .value_name = "N", .field = TS_SETTING(max_depth), .min = 1, .max = 100000,
     .unit = "vertices", .doc = "pt: scattering vertices per path, each lit by the lights (1: direct lighting)", .scope = ParameterScope::Pt},
    {.option = "--max-scatter", .value_name = "N", .field = TS_SETTING(max_scatter), .min = 0, .max = kNoMax,
     .unit = "vertices", .doc = "pt: medium scattering vertices per path (1: single scattering, 0: unlimited)", .scope = ParameterScope::Pt},
    {.option = "--tile", .value_name = "N", .field = TS_SETTING(igi.tile), .min = 1, .max = 8, .unit = "px",
     .doc = "igi: interleave tile edge n (n² sample sets)", .scope = ParameterScope::IgiFamily},
    {.option = "--vpl-paths", .value_name = "N", .field = TS_SETTING(igi.paths_per_set), .min = 1, .max = 65536,
     .unit = "paths", .doc = "igi: light paths per sample set (ic/tic: for a medium's light)", .scope = ParameterScope::IgiFamily},
    {.option = "--light-path-depth", .value_name = "N", .field = TS_SETTING(igi.light_path_depth), .min = 1,
     .max = 100000, .unit = "segments",
     .doc = "igi family: segments per light path at most (surface hits and medium scattering events)",
     .scope = ParameterScope::IgiFamily},
    {.option = "--vpl-importance", .value_name = "K", .field = TS_SETTING(igi.vpl_importance), .min = 1, .max = 64,
     .unit = "x", .doc = "igi family (ic/tic: for a medium's light): trace K× the light paths and keep a budget of VPLs by their importance for the view (1: off)", .scope = ParameterScope::IgiFamily},
    // At most 1: no two points of the scene (of frame 0, in an animation whose objects
    // move) lie farther apart than D, so c = 1 clamps every
    // VPL already, and a larger c only lowers b towards 0 (1e30 underflowed to b = 0 and
    // took all indirect light away, the opposite of what 0 means).
    {.option = "--clamp", .value_name = "C", .field = TS_SETTING(igi.clamp_c), .min = 0, .max = 1,
     .doc = "igi: VPL geometry clamp b = 1/(c·D)², D the scene's extent (its bounds' diagonal, specks left out; frame 0's where objects move); 0 disables", .scope = ParameterScope::IgiFamily},
    {.option = "--clamp-decay", .value_name = "A", .field = TS_SETTING(igi.clamp_decay), .min = 0, .max = 1,
     .doc = "igi: pass p clamps with c·(p+1)^-A, so accumulated passes converge to the unclamped image; 0: fixed", .scope = ParameterScope::IgiFamily},
    // At most 65536, as --vpl-paths: a pass cannot be interrupted, and 2^32 steps took
    // 25 minutes for one pixel's pass (the march costs ~0.35 us a step on one core).
    {.option = "--march-steps", .value_name = "N", .field = TS_SETTING(igi.march_steps), .min = 0, .max = 65536,
     .unit = "steps", .doc = "igi: medium ray-march steps per pixel (0: none, an error on a scene with a medium)", .scope = ParameterScope::IgiFamily},
    {.option = "--no-filter", .value_name = "", .field = TS_SETTING(igi.filter), .negated = true,
     .doc = "igi: skip the discontinuity filter", .scope = ParameterScope::IgiFamily},
    {.option = "--single-scattering", .value_name = "", .field = TS_SETTING(igi.multiple_scattering), .negated = true,
     .doc = "igi family: media: single scattering from the lights only (default: also VPLs at scattering events in the medium)", .scope = ParameterScope::IgiFamily},
    {.option = "--point-medium-vpls", .value_name = "", .field = TS_SETTING(igi.ray_lights), .negated = true,
     .doc = "igi family: media: the ray march gathers the medium VPLs as points, clamped (default: a virtual ray light per light-path segment in the medium, unclamped)", .scope = ParameterScope::IgiFamily},
    {.option = "--uniform-march", .value_name = "", .field = TS_SETTING(igi.equiangular), .negated = true,
     .doc = "igi family: media: light samples and VPLs gathered at the ray march's stratified points (default: at equiangular distances toward each)", .scope = ParameterScope::IgiFamily},
    {.option = "--no-mipmaps", .value_name = "", .field = TS_SETTING(texture_filter), .negated = true,
     .doc = "textures at camera hits from the finest mip level, not the pixel's ray-cone level (pt always)"},
    {.option = "--ais-ss-trigger", .value_name = "T", .field = TS_SETTING(igi.ais.ss_trigger), .min = 0, .max = 1,
     .doc = "ais: SS guidance trigger (flag where the light-visibility range exceeds it)", .scope = ParameterScope::Ais},
    {.option = "--ais-id-trigger", .value_name = "T", .field = TS_SETTING(igi.ais.id_trigger), .min = 0, .max = 1,
     .doc = "ais: ID guidance trigger", .scope = ParameterScope::Ais},
    {.option = "--ais-id-cov", .value_name = "C", .field = TS_SETTING(igi.ais.id_cov), .min = 0, .max = kNoMax,
     .min_exclusive = true, .doc = "ais: coefficient of variation of indirect light that saturates ID guidance", .scope = ParameterScope::Ais},
    {.option = "--ais-pm-trigger", .value_name = "T", .field = TS_SETTING(igi.ais.pm_trigger), .min = 0, .max = 1,
     .doc = "ais: PM guidance trigger", .scope = ParameterScope::Ais},
    {.option = "--ais-pm-cov", .value_name = "C", .field = TS_SETTING(igi.ais.pm_cov), .min = 0, .max = kNoMax,
     .doc = "ais: coefficient of variation of in-scattered light that saturates PM guidance (0: off)", .scope = ParameterScope::Ais},
    {.option = "--ais-complete", .value_name = "N", .field = TS_SETTING(igi.ais.complete_sets), .min = 0, .max = 64,
     .unit = "sets", .doc = "ais: distinct sets a flagged edge pixel completes its window to (0: ⌈N/2⌉, N: all)", .scope = ParameterScope::Ais},
    {.option = "--ais-graded-sets", .value_name = "G", .field = TS_SETTING(igi.ais.graded_sets), .min = 0, .max = 64,
     .unit = "sets", .doc = "ais: A gives a flagged pixel ⌈a·(min(G, N)−1)⌉ sets graded by its guidance a (0: G = N)", .scope = ParameterScope::Ais},
    {.option = "--ais-edge-samples", .value_name = "N", .field = TS_SETTING(igi.edges.samples), .min = 1, .max = 15,
     .unit = "samples", .doc = "ais: extra camera samples an edge pixel takes at most (ais-max: all)", .scope = ParameterScope::Ais},
    {.option = "--ais-edge-trigger", .value_name = "T", .field = TS_SETTING(igi.edges.trigger), .min = 0, .max = 1,
     .doc = "ais: edge guidance trigger (flag where the contrast across a geometric edge exceeds it)", .scope = ParameterScope::Ais},
    {.option = "--ic-paths", .value_name = "N", .field = TS_SETTING(ic.paths), .min = 1, .max = 65536,
     .unit = "paths", .doc = "ic/tic: light paths N_p a record gathers from", .scope = ParameterScope::Ic},
    {.option = "--ic-subsets", .value_name = "M", .field = TS_SETTING(ic.subsets), .min = 0, .max = 64,
     .unit = "subsets", .doc = "ic/tic: a pass draws M·N_p paths in M subsets, each record gathering from one (0: 1 below 4 spp, 2 below 16, else 16 from 256² pixels, 4 below)", .scope = ParameterScope::Ic},
    {.option = "--ic-importance", .value_name = "K", .field = TS_SETTING(ic.path_importance), .min = 1, .max = 64,
     .unit = "x", .doc = "ic/tic: trace K× the light paths and keep N_p paths' worth of VPLs, whole paths, by their importance for the view (1: off)", .scope = ParameterScope::Ic},
    {.option = "--ic-view-rays", .value_name = "S", .field = TS_SETTING(ic.view_rays), .min = 0, .max = 64,
     .unit = "rays", .doc = "ic/tic: shadow rays a candidate VPL traces toward the view points it lights, so unseen light weighs nothing in the choice (0: off)", .scope = ParameterScope::Ic},
    {.option = "--ic-error", .value_name = "A", .field = TS_SETTING(ic.error_bound), .min = 0.001, .max = 2,
     .doc = "ic/tic: Ward's error bound a", .scope = ParameterScope::Ic},
    {.option = "--no-clamp-compensation", .value_name = "", .field = TS_SETTING(igi.clamp_compensation), .negated = true,
     .doc = "igi family: skip the estimate of the light the VPL clamp removed (igi/ais: from the screen; ic/tic: up to two rays a pixel and pass)", .scope = ParameterScope::IgiFamily},
};

#undef TS_SETTING

// Shortest text that reads back as the same value ("0.05" for 0.05f, not 0.0500000007).
template <class T>
std::string shortest(T v) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

// A range bound of p: an integer for integer fields, else the shortest double.
std::string bound_text(const Parameter& p, double v) {
    return is_integer(p) ? std::to_string(static_cast<long long>(v)) : shortest(v);
}

// The field's value in `s` as text, in its own type.
std::string value_text(const Parameter& p, const RenderSettings& s) {
    // The accessors take a mutable RenderSettings; this only reads through them.
    RenderSettings& m = const_cast<RenderSettings&>(s);
    return std::visit([&](auto get) -> std::string {
        const auto v = get(m);
        if constexpr (std::is_same_v<decltype(v), const bool>)
            return v != p.negated ? "on" : "off";
        else if constexpr (std::is_integral_v<decltype(v)>)
            return std::to_string(v);
        else
            return shortest(v);
    }, p.field);
}

}  // namespace

bool is_flag(const Parameter& p) { return std::holds_alternative<bool& (*)(RenderSettings&)>(p.field); }

bool is_integer(const Parameter& p) {
    return std::holds_alternative<uint32_t& (*)(RenderSettings&)>(p.field) ||
           std::holds_alternative<int& (*)(RenderSettings&)>(p.field);
}

std::span<const Parameter> render_parameters() { return kParameters; }

bool parameter_applies(const Parameter& p, Method method) {
    const MethodInfo& m = method_info(method);
    switch (p.scope) {
    case ParameterScope::All: return true;
    case ParameterScope::Pt: return method == Method::PathTrace;
    case ParameterScope::IgiFamily: return m.igi_family;
    case ParameterScope::Ais: return m.adaptive;
    case ParameterScope::Ic: return method == Method::Ic || method == Method::Tic;
    }
    return true;
}

const char* parameter_scope_text(const Parameter& p) {
    switch (p.scope) {
    case ParameterScope::All: return "every method";
    case ParameterScope::Pt: return "pt";
    case ParameterScope::IgiFamily: return "igi, ais, ais-max, ic and tic";
    case ParameterScope::Ais: return "ais and ais-max";
    case ParameterScope::Ic: return "ic and tic";
    }
    return "";
}

const Parameter* find_parameter(const std::string& option) {
    for (const Parameter& p : kParameters)
        if (option == p.option) return &p;
    return nullptr;
}

double parameter_value(const Parameter& p, const RenderSettings& s) {
    RenderSettings& m = const_cast<RenderSettings&>(s);  // read only
    return std::visit([&](auto get) { return static_cast<double>(get(m)); }, p.field);
}

void validate_parameter(const Parameter& p, const RenderSettings& s) {
    if (is_flag(p)) return;
    const double v = parameter_value(p, s);
    if (p.zero_unset && v == 0) return;
    const bool above_min = p.min_exclusive ? v > p.min : v >= p.min;
    if (above_min && v <= p.max) return;  // false for NaN
    const std::string range = range_text(p);
    throw InputError(std::string(p.option) + " " + value_text(p, s) + ": must be " +
                     (range[0] == '>' ? range : "in " + range));
}

std::string check_parameter_text(const Parameter& p, const std::string& text) {
    const std::string range = range_text(p);
    const std::string in_range = range[0] == '>' ? range : "in " + range;
    const std::string shown = text.empty() ? "''" : text;
    auto fail = [&](const std::string& what) { throw InputError(std::string(p.option) + " " + shown + ": must be " + what); };
    // Decimal only: no sign but '-', no hex, no spaces, no trailing text.
    const char* b = text.data();
    const char* e = b + text.size();
    const bool negative = !text.empty() && text[0] == '-';
    double v = 0;
    if (is_integer(p)) {
        if (text.size() <= size_t(negative) || text.find_first_not_of("0123456789", negative) != std::string::npos)
            fail("an integer " + in_range);
        long double wide = 0;
        for (const char* c = b + negative; c != e; ++c) wide = wide * 10 + (*c - '0');
        v = double(negative ? -wide : wide);
    } else {
        const auto r = std::from_chars(b, e, v);
        if (text.empty() || r.ec == std::errc::invalid_argument || r.ptr != e) fail("a number " + in_range);
        if (r.ec == std::errc::result_out_of_range || !std::isfinite(v)) fail("a finite number " + in_range);
    }
    if (p.zero_unset && v == 0) fail(in_range + " (leave the option out for the scene camera's)");
    const bool above_min = p.min_exclusive ? v > p.min : v >= p.min;
    if (!above_min || v > p.max) fail(in_range);
    // Within p's range but beyond the field type's: only open ranges ("--seed" is a uint32_t).
    std::visit([&](auto get) {
        using T = std::remove_reference_t<decltype(get(std::declval<RenderSettings&>()))>;
        if (v > double(std::numeric_limits<T>::max())) {
            Parameter bounded = p;
            bounded.max = double(std::numeric_limits<T>::max());
            fail("in " + range_text(bounded));
        }
    }, p.field);
    if (!is_integer(p)) return text;
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, static_cast<long long>(v));
    return std::string(buf, r.ptr);  // canonical: CLI11 would read "010" as octal
}

void validate_settings(const RenderSettings& s) {
    for (const Parameter& p : kParameters) validate_parameter(p, s);
}

std::string range_text(const Parameter& p) {
    if (is_flag(p)) return "flag";
    const std::string lo = bound_text(p, p.min);
    // An open range of an integer field ends at its type's largest value ("--seed" is a
    // uint32_t: 0..4294967295).
    if (std::isinf(p.max) && is_integer(p)) {
        Parameter bounded = p;
        std::visit([&](auto get) {
            using T = std::remove_reference_t<decltype(get(std::declval<RenderSettings&>()))>;
            bounded.max = double(std::numeric_limits<T>::max());
        }, p.field);
        return range_text(bounded);
    }
    if (std::isinf(p.max)) return (p.min_exclusive ? "> " : ">= ") + lo;
    if (is_integer(p)) return lo + ".." + bound_text(p, p.max);
    return (p.min_exclusive ? "(" : "[") + lo + ", " + bound_text(p, p.max) + "]";
}

std::string default_text(const Parameter& p) {
    static const RenderSettings defaults;
    if (is_flag(p)) return "off";  // a flag's default is its absence
    if (p.zero_unset && parameter_value(p, defaults) == 0) return "camera";
    return value_text(p, defaults);
}

std::string options_markdown() {
    std::string md = "| option | default | range | unit | description |\n|---|---|---|---|---|\n";
    for (const Parameter& p : kParameters) {
        const std::string name = *p.value_name ? std::string(p.option) + " " + p.value_name : p.option;
        md += "| `" + name + "` | " + default_text(p) + " | " + range_text(p) + " | " + p.unit + " | " + p.doc +
              " |\n";
    }
    return md;
}

}  // namespace tessera
