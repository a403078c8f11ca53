/* The igi composite of one pixel from its components, tracer-free so that the host's
 * frame (host/integrators/igi_frame.cpp, after filtering or AIS reconstruction) uses the one
 * formula of the transport model of shared/igi.h:
 *   L = Tr · β · (Le + ρ · (E_ss + E_id)) + L_pm
 * with Tr the transmittance of the camera segment (TS_IGI_MEDIA_TRANSMITTANCE; 1 without
 * a medium), β the throughput of the specular bounces before the surface
 * (TS_IGI_SURF_THROUGHPUT), Le the emission seen, ρ the albedo, E_ss and E_id the direct
 * and indirect irradiance / π, and L_pm the single-scattered radiance of the segment
 * (TS_IGI_MEDIA_RADIANCE). All radiance in W/(sr·m²). */
#ifndef TS_COMPOSITE_H
#define TS_COMPOSITE_H
#include "shared/compat.h"

TS_NAMESPACE_BEGIN

TS_INLINE float3 ts_igi_composite(float3 transmittance, float3 throughput, float3 emission, float3 albedo,
                                  float3 e_ss, float3 e_id, float3 l_pm) {
    return transmittance * throughput * (emission + albedo * (e_ss + e_id)) + l_pm;
}

TS_NAMESPACE_END
#endif /* TS_COMPOSITE_H */
