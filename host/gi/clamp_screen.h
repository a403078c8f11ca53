// The screen-space compensation of the VPL clamp for igi-family frames: what the
// geometry-term clamp removed, estimated per pixel from the frame's G-buffer and its
// reconstructed irradiance (kernels/shared/clamp_screen.h; Novák, Engelhardt and
// Dachsbacher 2011; docs/igi.md §4). Host code shared by every backend.
#pragma once
#include <vector>

#include "gi/discontinuity_filter.h"
#include "kernels/shared/frame.h"
#include "kernels/shared/medium.h"

namespace tessera {

/// Inputs of one frame, per pixel, row-major (g.width × g.height):
/// - `g`: the G-buffer (positions, unit normals, depth; +inf depth where the ray escaped);
/// - `albedo`, `throughput`: 3 floats a pixel, as the igi surface kernel writes them
///   (TS_IGI_SURF_ALBEDO, TS_IGI_SURF_THROUGHPUT); a pixel seen through a specular bounce
///   (throughput ≠ 1) neither gets nor sends compensation, its screen neighbours not being
///   its surface's;
/// - `e_ss`, `e_id`: the reconstructed direct and indirect irradiance / π (3 floats a
///   pixel).
struct ClampScreenInputs {
    const GeometryBuffer* g = nullptr;
    const std::vector<float>* albedo = nullptr;      ///< stride `stride`, offset albedo_at
    const std::vector<float>* throughput = nullptr;  ///< stride `stride`, offset throughput_at
    int stride = 3, albedo_at = 0, throughput_at = 0;
    const std::vector<float>* e_ss = nullptr;
    const std::vector<float>* e_id = nullptr;
    /// Which neighbours lie on a pixel's surface (the frame's discontinuity test): a pixel
    /// off the half-resolution grid takes the mean of those grid neighbours' E_res.
    DiscontinuitySettings same_surface;
};

/// E_res per pixel (3 floats, irradiance / π, W/m² / π) for clamp b (scene units⁻²; +inf
/// or 0: zeros), `frame`'s camera and medium `med` (nullptr: none), in `residual`
/// (resized). `planes`: scratch for the gather's records (kernels/shared/clamp_screen16.h;
/// resized to 40 + 6,400 / width bytes a pixel, 52.5 at 512 wide), which a caller keeps so
/// that its frames reuse the memory. TBB-parallel over rows; deterministic.
void clamp_screen_residual(const TsFrame& frame, float b, const ts::TsMedium* med, const ClampScreenInputs& in,
                           std::vector<float>& residual, std::vector<float>& planes);
/// The same with scratch of its own.
inline void clamp_screen_residual(const TsFrame& frame, float b, const ts::TsMedium* med, const ClampScreenInputs& in,
                                  std::vector<float>& residual) {
    std::vector<float> planes;
    clamp_screen_residual(frame, b, med, in, residual, planes);
}

}  // namespace tessera
