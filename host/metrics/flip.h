// Mean HDR-FLIP error, computed by NVIDIA's reference implementation of FLIP (the PyPI
// package `flip-evaluator`) through the script bench/flip_metric.py, run as a subprocess.
// FLIP is not reimplemented in C++: the reference implementation is the definition.
// Sources: Andersson et al., "FLIP: A Difference Evaluator for Alternating Images", HPG
// 2020; "Visualizing Errors in Rendered High Dynamic Range Images", EG 2021 (HDR-FLIP).
#pragma once
#include <filesystem>
#include <optional>
#include <string>

namespace tessera::metrics {

/// FLIP statistics of a test image against a reference (HDR mode, package defaults:
/// 67 pixels per degree, ACES tone mapper, automatic exposure range).
struct FlipResult {
    bool available = false;
    std::string reason;          ///< why FLIP is unavailable (when !available)
    double mean = 0.0;           ///< mean FLIP error over pixels, in [0, 1]
    double pct_gt_0_1 = 0.0;     ///< % of pixels with FLIP error > 0.1
    double pct_gt_0_3 = 0.0;     ///< % of pixels with FLIP error > 0.3
    std::string implementation;  ///< e.g. "flip-evaluator 1.7"
};

/// Runs `python3 flip_metric.py REF TEST [--map MAP]` and parses its JSON. The interpreter
/// is $TESSERA_PYTHON (default `python3` on PATH); the script is $TESSERA_FLIP_SCRIPT
/// (default TESSERA_SOURCE_DIR/bench/flip_metric.py). Never throws for a missing
/// interpreter, script or package, or a failing script: returns available = false with
/// the reason, so the other metrics are still reported.
FlipResult compute_flip(const std::filesystem::path& ref, const std::filesystem::path& test,
                        const std::optional<std::filesystem::path>& map_png = std::nullopt);

}  // namespace tessera::metrics
