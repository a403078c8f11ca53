// What one input may cost: the bounds every reader checks before it allocates, so that a
// hostile or broken file is rejected in well under a second and a few MB of memory
// (docs/input-limits.md lists them for users). Each bound is far above any real input of
// its kind; the reason for each value is beside it.
#pragma once
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "util/error.h"

namespace tessera::limits {

/// A number of a scene file (JSON) or material (MTL) that is not 0 but below the smallest
/// normal float (1.2e-38) as a float, or that rounds to 0: refused. The CPU path runs
/// with Embree's flush-to-zero and denormals-are-zero modes, and OpenCL devices need not
/// keep subnormals either, so the backends rendered an emission of 1e-40 as 0 and as
/// 1e-40; no physical scene value is that small. Readers say "give 0". (OBJ geometry is
/// not checked: exporters print such values for 0, and a position 1e-45 from 0 renders
/// as 0 on both backends.)
inline bool below_normal_float(double d) { return d != 0.0 && !(std::fabs(float(d)) >= FLT_MIN); }

/// The words of that refusal, after the value.
constexpr const char* kBelowNormalFloat = "is below the smallest normal float, 1.2e-38 (give 0)";

/// Bytes of one JSON file (scene, camera path, input script). The largest shipped scene
/// file is a few kB and a 10,000-frame camera path about 2 MB; 64 MiB leaves 30x room.
constexpr std::uintmax_t kJsonFileBytes = std::uintmax_t(64) << 20;

/// Nesting depth of JSON arrays and objects. Scene files nest 5 deep at most (an object's
/// animation keys' vectors); 64 keeps every legitimate file and stops a `[[[[...` bomb
/// after 64 levels of parser state.
constexpr int kJsonDepth = 64;

/// Bytes of one OBJ or MTL file, read into memory whole: 2 GiB is the largest size the
/// 32-bit vertex and index counts of the scanner can describe in practice.
constexpr std::uintmax_t kMeshFileBytes = std::uintmax_t(2) << 30;

/// Bytes of one texture file, read into memory whole: twice the 1 GiB of a 16384 x 16384
/// RGBA PNG stored without compression, the largest texture of the image side limit.
constexpr std::uintmax_t kTextureFileBytes = (std::uintmax_t(1) << 31) - 1;

/// Pixels on either side of an input image (texture, `compare` and `--reference` EXR,
/// checkpoint): the same bound as --width and --height (render/parameters.cpp).
constexpr int kImageSide = 16384;

/// Float values (pixels times channels) of one input EXR: 2^28 floats are 1 GiB, enough
/// for a 16384 x 16384 single-channel or 8192 x 8192 x 4 image, and bound what a header
/// with a huge data window (a file of a few bytes) makes the reader allocate.
constexpr std::uint64_t kImageFloats = std::uint64_t(1) << 28;

/// Entries of a camera path and events of an input script: 10^6 frames are 9 hours at
/// 30 fps, far beyond a fly-through, and keep a hostile file's parse under a second.
constexpr std::size_t kPathEntries = 1000000;

/// Viewer frame numbers in an input script (0-based) and animation frames in a camera path
/// stay below this: the same 10^6 as kPathEntries, so a script cannot ask the headless
/// viewer for days of frames before its first event.
constexpr int kViewFrames = 1000000;

/// Emitted radiance per channel, W/(sr·m²) (MTL Ke, JSON emission and light radiance).
/// The Sun's disc is about 2·10^7. The estimators multiply radiance by factors (1/pdf,
/// a VPL's flux, the instant cache's sums) that took an emission of 10^36 past the float
/// range (ic and tic wrote Inf; 3·10^38 gave NaN in igi); 10^15 leaves 10^23 of room.
constexpr float kMaxRadiance = 1e15f;

/// Scene coordinates, scene units: every vertex of a mesh (after its object's transform)
/// and every corner of a JSON light lies within ±10^10 of the origin (in metres, 70 times
/// the Earth–Sun distance). Squared distances and areas (up to about 10^21) times the
/// brightest radiance (kMaxRadiance) stay far inside the float range. Past it, a scale of
/// 10^30 overflowed the emitters' areas (an error that named no key, or blamed the
/// medium), and a translation of 3·10^38 collapsed a room onto one float and dropped its
/// lamp without a word.
constexpr float kMaxCoordinate = 1e10f;

/// A medium's optical depth over the scene's diagonal D, (σ_a + σ_s)·D per channel.
/// Transmittance exp(−τ) is 0 in float past τ ≈ 104, so at 10^9 the medium is opaque
/// past 10^-7 of the diagonal and any denser one renders the same; the ray march's
/// products of σ with distances and radiance then stay far from the float range
/// (σ_s = 5·10^37 on the Cornell box gave NaN pixels in every igi-family method).
constexpr double kMaxOpticalDepth = 1e9;

/// Exposure in stops (render's PNG preview, compare's tone map, the viewer's display): the
/// image is scaled by 2^exposure in float, and 2^128 overflows it. ±64 stops scale the
/// brightest radiance accepted (kMaxRadiance, 2^50) to 2^114 or the dimmest normal float
/// up to 2^-62, both finite; 64 stops are far more than any display's range.
constexpr double kExposureStops = 64.0;

/// A limit or bound as messages show it: "%g" ("0", "240", "1e+12").
inline std::string shown_limit(double limit) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", limit);
    return text;
}

/// kMaxCoordinate as the scene loaders' messages state it, with its unit and reason.
inline std::string shown_coordinate_limit() {
    return "the limit of ±" + shown_limit(kMaxCoordinate) +
           " scene units on each axis (farther, areas and the lights' power leave the float range, or the floats "
           "lose the shape)";
}

/// kMaxRadiance as the scene loaders' messages state it, with its unit and reason.
inline std::string shown_radiance_limit() {
    return shown_limit(kMaxRadiance) + " W/(sr·m²) (brighter overflows the estimators' float sums)";
}

/// Throws InputError "<file>: <what> of <w>x<h> pixels exceeds ..." when an image header
/// asks for more than kImageSide per side or (with `channels` > 0) kImageFloats values,
/// before anything is allocated. `what` names the role ("texture", "EXR image").
inline void check_image_size(const std::string& what, const std::string& file, long long width, long long height,
                             long long channels) {
    const std::string head = file + ": " + what + " of " + std::to_string(width) + "x" + std::to_string(height) + " pixels";
    if (width < 1 || height < 1) throw InputError(head + " is empty");
    if (width > kImageSide || height > kImageSide)
        throw InputError(head + " exceeds the limit of " + std::to_string(kImageSide) + " pixels per side");
    if (channels > 0 && std::uint64_t(width) * std::uint64_t(height) * std::uint64_t(channels) > kImageFloats)
        throw InputError(head + " and " + std::to_string(channels) + " channels exceeds the limit of 2^28 values (1 GiB)");
}

}  // namespace tessera::limits
