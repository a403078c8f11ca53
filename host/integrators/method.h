// The rendering methods (--method): one table row per method (method_table.cpp) says what
// it is, and every switch and predicate over methods — the commands, the viewer, the
// factory, the tests — reads it. Adding a method: its integrator files, a Method value
// and one row (docs/ARCHITECTURE.md, "Where to add").
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace tessera {

class Backend;
class Integrator;
struct Scene;
struct SceneBuffers;
struct IntegratorSettings;

enum class Method {
    Direct,     ///< emission + direct light from area lights (kernels/shared/direct.h)
    PathTrace,  ///< volumetric path tracing, the reference (kernels/shared/pt.h)
    Igi,        ///< instant global illumination (kernels/shared/igi.h, host/gi)
    Ais,        ///< adaptive interleaved sampling, mode A (host/gi/ais_schedule.h)
    AisMax,     ///< adaptive interleaved sampling, mode A-MAX
    Ic,         ///< instant caching: igi with indirect light from an irradiance cache (host/gi/instant_cache.h)
    Tic,        ///< temporal instant caching: the cache kept and updated across frames
};

/// Makes a method's integrator (integrators/factory.h says what the arguments must be).
using MakeIntegratorFn = std::unique_ptr<Integrator> (*)(Backend&, const Scene&, const SceneBuffers&,
                                                         const IntegratorSettings&);
/// Makes the state a method keeps across the frames of a sequence of `rest` (in the settings).
using PrepareSequenceFn = void (*)(IntegratorSettings&, const Scene& rest);

/// What a method is. One row per Method, in Method order.
struct MethodInfo {
    Method method;
    const char* name;        ///< its --method name
    const char* summary;     ///< one line: what it computes
    /// Built on VPLs and interleaved sampling: takes --components, marches media by the igi
    /// settings, reads IgiSettings (else it is one kernel per pass: direct, pt).
    bool igi_family;
    /// Adaptive interleaved sampling: guidance and sets AOVs, edge samples (--components edge).
    bool adaptive;
    /// Keeps state from one pass and frame to the next (prepare): a checkpoint cannot hold
    /// it (no --resume) and its passes cannot be split over MPI ranks.
    bool temporal;
    /// Adds AOV channels of its own (sums one process keeps: not under MPI).
    bool own_aovs;
    /// Computes all bounces of light (else emission and one bounce of direct light).
    bool global;
    /// Renders participating media (else it ignores them).
    bool media;
    MakeIntegratorFn make;
    PrepareSequenceFn prepare;  ///< null: nothing kept across frames
};

/// Every method, in Method order.
const std::vector<MethodInfo>& method_table();
/// The row of `m`.
const MethodInfo& method_info(Method m);

/// Parses a table name ("direct", "pt", "igi", "ais", "ais-max", "ic", "tic"); throws
/// InputError naming --method and listing the names otherwise.
Method parse_method(const std::string& name);
const char* method_name(Method m);
/// The table's names, comma-separated ("direct, pt, igi, ...").
std::string method_names();

/// method_info(m).igi_family: the one definition every command and the viewer use.
bool igi_family(Method m);

/// Parses a comma-separated list of "ss", "id", "pm", "edge" (AIS's edge samples) into
/// TS_COMPONENT_* bits; throws
/// InputError naming --components for anything else, an empty entry or a component
/// listed twice ("ss,ss").
uint32_t parse_components(const std::string& list);

/// The --components list of a TS_COMPONENT_* mask, e.g. "ss,id,pm" ("none" for 0).
std::string components_text(uint32_t mask);

}  // namespace tessera
