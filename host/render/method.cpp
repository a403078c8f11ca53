#include "render/method.h"

#include "kernels/shared/layout.h"
#include "util/error.h"

namespace tessera {

Method parse_method(const std::string& name) {
    if (name == "direct") return Method::Direct;
    if (name == "pt") return Method::PathTrace;
    if (name == "igi") return Method::Igi;
    throw InputError("--method " + name + ": not available (implemented: direct, pt, igi)");
}

const char* method_name(Method m) {
    switch (m) {
        case Method::Direct: return "direct";
        case Method::PathTrace: return "pt";
        case Method::Igi: return "igi";
    }
    return "?";
}

int pixel_kernel_floats(PixelKernel k) {
    switch (k) {
        case PixelKernel::Direct:
        case PixelKernel::PathTrace: return TS_PASS_FLOATS;
        case PixelKernel::IgiSurface: return TS_IGI_SURF_FLOATS;
        case PixelKernel::IgiMedia: return TS_IGI_MEDIA_FLOATS;
    }
    return 0;
}

const char* pixel_kernel_name(PixelKernel k) {
    switch (k) {
        case PixelKernel::Direct: return "direct_pass";
        case PixelKernel::PathTrace: return "pt_pass";
        case PixelKernel::IgiSurface: return "igi_surface_pass";
        case PixelKernel::IgiMedia: return "igi_media_pass";
    }
    return "?";
}

}  // namespace tessera
