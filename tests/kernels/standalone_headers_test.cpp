// Every kernel header compiles by itself: each includes what it uses, so a header can be
// read, moved or included first without knowing which other header must come before it.
// As OpenCL C here (every header under kernels/, on the OpenCL device the tests use); as
// C++ the shared headers each get a translation unit of their own in the test binary
// (tests/CMakeLists.txt), so one that does not compile alone fails the build. A shared
// header that traces rays is given the backend's tracer first (its interface).
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "opencl/cl.h"
#include "opencl/device.h"
#include "opencl/kernel_source.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> kernel_headers() {
    const fs::path root = fs::path(TESSERA_SOURCE_DIR) / "kernels";
    std::vector<std::string> headers;
    for (const auto& e : fs::recursive_directory_iterator(root))
        if (e.path().extension() == ".h") headers.push_back(fs::relative(e.path(), root).generic_string());
    return headers;
}

TEST(StandaloneHeaders, EveryKernelHeaderCompilesAloneAsOpenClC) {
    const std::vector<std::string> headers = kernel_headers();
    ASSERT_GE(headers.size(), 20u) << "kernels/ should hold the shared headers";
    const ClDeviceInfo dev = select_cl_device("");
    const cl::Context ctx(dev.device);
    for (const std::string& h : headers) {
        // The source is the header alone, its own includes expanded (as build_program does);
        // a shared header that traces rays first gets the OpenCL tracer, its documented
        // interface (shared/direct.h: "The including backend must first define TsTracer").
        const std::string text = load_kernel_source(h);
        // The packet tracer (ts_trace_*_lanes, shared/igi_view16.h) comes from igi_packets.h.
        const bool tracer = h.rfind("shared/", 0) == 0 && text.find("TsTracer") != std::string::npos;
        const bool lanes = tracer && text.find("_lanes(const TsTracer*") != std::string::npos;
        const std::string before = lanes ? load_kernel_source("igi_packets.h") : tracer ? load_kernel_source("tracer.h") : "";
        cl::Program program(ctx, before + text);
        std::string log;
        try {
            program.build({dev.device}, "-cl-std=CL1.2");
        } catch (const cl::Error&) {
            log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(dev.device);
            ADD_FAILURE() << h << " does not compile by itself:\n" << log;
        }
    }
}

}  // namespace
}  // namespace tessera
