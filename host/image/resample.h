// Resizing images for display: the viewer renders moving frames at a fraction of the
// window's resolution (docs/viewer.md §4) and shows them upsampled.
#pragma once
#include "image/image_io.h"

namespace tessera {

/// `src` resized to width × height by bilinear interpolation (pixel centres aligned: the
/// source position of output pixel x is (x + 0.5)·src.width/width − 0.5, clamped to the
/// image), every channel alike, x0/y0 kept. Where a tap with non-zero weight is not finite
/// (Z is +inf where the camera ray missed) the output takes the nearest tap's value, so no
/// inf·0 makes a NaN. Throws std::invalid_argument for a size < 1 or an empty `src`.
Image resize_bilinear(const Image& src, int width, int height);

}  // namespace tessera
