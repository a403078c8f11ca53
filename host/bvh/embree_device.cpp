#include "bvh/embree_device.h"

#include <pmmintrin.h>
#include <xmmintrin.h>

#include <string>
#include <utility>

#include "util/error.h"

namespace tessera {
namespace {

// Embree reports an error's text only to the device's error function, called on the
// thread whose API call failed; check_embree on that thread adds it to the exception.
thread_local std::string last_embree_message;

void record_embree_error(void*, RTCError, const char* message) { last_embree_message = message ? message : ""; }

}  // namespace

RTCDevice embree_device() {
    static RTCDevice device = [] {
        RTCDevice d = rtcNewDevice("frequency_level=simd256");
        if (!d) throw RuntimeError("Embree: rtcNewDevice failed (error " +
                                   std::to_string(rtcGetDeviceError(nullptr)) + ")");
        rtcSetDeviceErrorFunction(d, record_embree_error, nullptr);
        return d;
    }();
    return device;
}

void check_embree(const char* what) {
    RTCError e = rtcGetDeviceError(embree_device());
    if (e != RTC_ERROR_NONE) {
        std::string message = std::move(last_embree_message);
        last_embree_message.clear();
        throw RuntimeError(std::string("Embree: ") + what + " failed (error " + std::to_string(static_cast<int>(e)) +
                           (message.empty() ? "" : ": " + message) + ")");
    }
}

FtzDazScope::FtzDazScope() : saved_(_mm_getcsr()) {
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

FtzDazScope::~FtzDazScope() { _mm_setcsr(saved_); }

}  // namespace tessera
