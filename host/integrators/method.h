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

/// Parses a comma-separated list of "ss", "id", "pm" into TS_COMPONENT_* bits; throws
/// InputError naming --components for anything else or an empty list.
uint32_t parse_components(const std::string& list);

}  // namespace tessera
