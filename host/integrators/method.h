// The rendering methods (--method) and their names.
#pragma once
#include <cstdint>
#include <string>

namespace tessera {

enum class Method {
    Direct,     ///< emission + direct light from area lights (kernels/shared/direct.h)
    PathTrace,  ///< volumetric path tracing, the reference (kernels/shared/pt.h)
    Igi,        ///< instant global illumination (kernels/shared/igi.h, host/gi)
    Ais,        ///< adaptive interleaved sampling, mode A (host/gi/ais_schedule.h)
    AisMax,     ///< adaptive interleaved sampling, mode A-MAX
    Ic,         ///< instant caching: igi with indirect light from an irradiance cache (host/gi/instant_cache.h)
    Tic,        ///< temporal instant caching: the cache kept and updated across frames
};

/// Parses "direct", "pt", "igi", "ais", "ais-max", "ic" or "tic"; throws InputError naming --method
/// otherwise.
Method parse_method(const std::string& name);
const char* method_name(Method m);

/// True for the methods built on VPLs and interleaved sampling (igi, ais, ais-max, ic,
/// tic): they take --components, march media and read the igi settings; direct and pt
/// do not. The one definition every command and the viewer use.
bool igi_family(Method m);

/// Parses a comma-separated list of "ss", "id", "pm", "edge" (AIS's edge samples) into
/// TS_COMPONENT_* bits; throws
/// InputError naming --components for anything else, an empty entry or a component
/// listed twice ("ss,ss").
uint32_t parse_components(const std::string& list);

}  // namespace tessera
