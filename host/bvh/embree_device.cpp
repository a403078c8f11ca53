#include "bvh/embree_device.h"

#include <pmmintrin.h>
#include <xmmintrin.h>

#include <string>

#include "util/error.h"

namespace tessera {

RTCDevice embree_device() {
    static RTCDevice device = [] {
        RTCDevice d = rtcNewDevice("frequency_level=simd256");
        if (!d) throw RuntimeError("Embree: rtcNewDevice failed (error " +
                                   std::to_string(rtcGetDeviceError(nullptr)) + ")");
        return d;
    }();
    return device;
}

void check_embree(const char* what) {
    RTCError e = rtcGetDeviceError(embree_device());
    if (e != RTC_ERROR_NONE)
        throw RuntimeError(std::string("Embree: ") + what + " failed (error " +
                           std::to_string(static_cast<int>(e)) + ")");
}

void set_ftz_daz() {
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

}  // namespace tessera
