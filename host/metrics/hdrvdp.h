// HDR-VDP-3 (Mantiuk et al. 2023; the maintained successor of the HDR-VDP the seed thesis
// validates with, its Table 5.3), computed by bench/hdrvdp_metric.py in GNU Octave, run as a
// subprocess. An optional metric: it needs Octave with its statistics and image packages and
// the HDR-VDP-3 sources (bench/README.md, "Perceptual metric: HDR-VDP-3", says where they
// are looked for). The protocol (the same section and the script's docstring): both images
// scaled so that the reference's mean luminance is 100 cd/m^2, 'rgb-native', 'side-by-side',
// 32.45 pixels per degree.
#pragma once
#include <filesystem>
#include <string>

namespace tessera::metrics {

/// HDR-VDP-3's verdict on a test image against a reference.
struct HdrvdpResult {
    double pct_p_ge_75 = 0.0;  ///< % of pixels whose probability of a visible difference is >= 75%
    double pct_p_ge_95 = 0.0;  ///< % of pixels with that probability >= 95%
    double q_jod = 0.0;        ///< pooled quality, JOD: 10 = no visible difference
    double ppd = 0.0;          ///< pixels per degree used
    std::string implementation;  ///< e.g. "hdrvdp-3.0.7 in GNU Octave, version 7.3.0"
};

/// Where the metric runs: `python` (python3, with numpy and OpenEXR) and the script,
/// $TESSERA_HDRVDP_SCRIPT, else TESSERA_SOURCE_DIR/bench/hdrvdp_metric.py.
struct HdrvdpTool {
    std::string python;
    std::filesystem::path script;
};
HdrvdpTool hdrvdp_tool();

/// Checks that the tool can run (`python3 hdrvdp_metric.py --check`: Octave, its packages
/// and the sources) and returns the implementation it reports. Throws InputError naming
/// `option` (e.g. "--hdrvdp") and the script's reason, with how to install what is missing.
std::string check_hdrvdp(const HdrvdpTool& tool, const std::string& option);

/// Runs the metric on two EXRs (same size, linear RGB radiance). Throws RuntimeError with
/// the script's message if it fails or prints something that is not its JSON.
HdrvdpResult compute_hdrvdp(const HdrvdpTool& tool, const std::filesystem::path& ref,
                            const std::filesystem::path& test);

}  // namespace tessera::metrics
