// ColorVideoVDP, a perceptual HDR-aware difference predictor (Mantiuk et al., "ColorVideoVDP:
// A visual difference predictor for image, video and display distortions", SIGGRAPH 2024;
// PyPI package `cvvdp`), computed by bench/cvvdp_metric.py, run as a subprocess with an
// interpreter that can import pycvvdp (it needs PyTorch, so it usually lives in a venv of
// its own: bench/README.md). The script states the viewing conditions; their defaults are
// the HDR-VDP-3 protocol's (bench/README.md, "Perceptual metric: HDR-VDP-3": 32.45 pixels
// per degree, the reference scaled to a mean luminance of 100 cd/m^2) on cvvdp's
// `standard_hdr_linear` display (peak 1500 cd/m^2).
#pragma once
#include <filesystem>
#include <optional>
#include <string>

namespace tessera::metrics {

/// ColorVideoVDP's verdict on a test image against a reference.
struct CvvdpResult {
    double jod = 0.0;             ///< pooled quality, JOD: 10 = no visible difference, lower = worse
    double pct_ge_1jod = 0.0;     ///< % of pixels whose distortion map is >= 1 JOD (0.1)
    double pct_ge_2_44jod = 0.0;  ///< % of pixels >= 2.44 JOD (0.2439): 95% of observers would choose
    double d_mean = 0.0;          ///< mean of the distortion map D = 1 - JOD_local / 10, in [0, 1]
    double ppd = 0.0;             ///< pixels per degree used
    double peak_cd_m2 = 0.0;      ///< display peak luminance used, cd/m^2
    double mean_luminance = 0.0;  ///< the reference's mean luminance after scaling, cd/m^2
    std::string display;          ///< cvvdp display photometry, e.g. "standard_hdr_linear"
    std::string implementation;   ///< e.g. "cvvdp 0.5.7, torch 2.9.0"
};

/// Where the metric runs: `python` (an interpreter that imports pycvvdp) and the script.
struct CvvdpTool {
    std::string python;
    std::filesystem::path script;
};

/// The tool `tessera compare --cvvdp` runs: the interpreter is `python_option` when not
/// empty (--cvvdp-python), else $TESSERA_CVVDP_PYTHON, else `python3` on PATH; the script
/// is $TESSERA_CVVDP_SCRIPT, else TESSERA_SOURCE_DIR/bench/cvvdp_metric.py.
CvvdpTool cvvdp_tool(const std::string& python_option);

/// Checks that the tool can run (`PYTHON cvvdp_metric.py --check`) and returns the
/// implementation it reports. Throws InputError naming `option` (e.g. "--cvvdp"), the
/// interpreter and the reason (not found, pycvvdp not importable), and how to install it.
std::string check_cvvdp(const CvvdpTool& tool, const std::string& option);

/// Runs the metric on two EXRs (same size, linear RGB radiance; `heatmap_png` also writes
/// cvvdp's threshold visualisation of the distortion map). Throws RuntimeError with the
/// script's message if it fails or prints something that is not its JSON.
CvvdpResult compute_cvvdp(const CvvdpTool& tool, const std::filesystem::path& ref,
                          const std::filesystem::path& test,
                          const std::optional<std::filesystem::path>& heatmap_png = std::nullopt);

}  // namespace tessera::metrics
