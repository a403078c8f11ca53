// The rendering methods (--method) and their names.
#pragma once
#include <string>

namespace tessera {

enum class Method {
    Direct,     ///< emission + direct light from area lights (kernels/shared/direct.h)
    PathTrace,  ///< volumetric path tracing, the reference (kernels/shared/pt.h)
    Igi,        ///< instant global illumination (kernels/shared/igi.h, host/gi)
};

/// Parses "direct", "pt" or "igi"; throws InputError naming --method otherwise.
Method parse_method(const std::string& name);
const char* method_name(Method m);

/// The per-pixel kernels a backend dispatches. A method runs one or more of them.
enum class PixelKernel {
    Direct,      ///< TS_PASS_FLOATS per pixel
    PathTrace,   ///< TS_PASS_FLOATS per pixel
    IgiSurface,  ///< TS_IGI_SURF_FLOATS per pixel
    IgiMedia,    ///< TS_IGI_MEDIA_FLOATS per pixel
};
constexpr int kPixelKernelCount = 4;

/// Floats each pixel of `k`'s output holds.
int pixel_kernel_floats(PixelKernel k);
const char* pixel_kernel_name(PixelKernel k);

}  // namespace tessera
