// OpenCL programs: include expansion, the on-disk binary cache, build-log reporting.
#include "opencl/program_cache.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "opencl/kernel_source.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace tessera {
namespace {

// Points an environment variable at a fresh directory for one test, then restores it.
class ScopedDirEnv {
public:
    ScopedDirEnv(const char* name, const std::string& tag) : name_(name) {
        dir_ = fs::temp_directory_path() / ("tessera-" + tag + "-" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        if (const char* old = std::getenv(name)) old_ = old, had_ = true;
        ::setenv(name, dir_.c_str(), 1);
    }
    ~ScopedDirEnv() {
        if (had_) ::setenv(name_, old_.c_str(), 1);
        else ::unsetenv(name_);
        fs::remove_all(dir_);
    }
    const fs::path& dir() const { return dir_; }

private:
    const char* name_;
    fs::path dir_;
    std::string old_;
    bool had_ = false;
};

TEST(KernelSource, IncludesAreExpandedOnce) {
    const std::string src = load_kernel_source("direct.cl");
    EXPECT_EQ(src.find("#include \""), std::string::npos);
    EXPECT_NE(src.find("ts_direct_pixel"), std::string::npos);
    // compat.h is included by several headers but appears once.
    const std::string marker = "#define TS_COMPAT_H";
    EXPECT_EQ(src.find(marker), src.rfind(marker));
}

TEST(ProgramCache, SecondBuildComesFromTheCache) {
    ScopedDirEnv cache("TESSERA_CACHE_DIR", "cache");
    ClDeviceInfo dev = select_cl_device("");
    cl::Context ctx(dev.device);
    ProgramBuild first = build_program(ctx, dev, "trace.cl", {});
    EXPECT_FALSE(first.from_cache);
    size_t entries = 0;
    for (const auto& e : fs::directory_iterator(cache.dir())) entries += e.path().extension() == ".bin";
    EXPECT_EQ(entries, 1u);
    ProgramBuild second = build_program(ctx, dev, "trace.cl", {});
    EXPECT_TRUE(second.from_cache);
    // Other defines are another program, not a cache hit.
    ProgramBuild third = build_program(ctx, dev, "trace.cl", {"-DTS_HAS_TEXTURES"});
    EXPECT_FALSE(third.from_cache);
}

TEST(ProgramCache, CorruptEntryIsRebuilt) {
    ScopedDirEnv cache("TESSERA_CACHE_DIR", "cache-corrupt");
    ClDeviceInfo dev = select_cl_device("");
    cl::Context ctx(dev.device);
    build_program(ctx, dev, "trace.cl", {});
    for (const auto& e : fs::directory_iterator(cache.dir())) std::ofstream(e.path(), std::ios::trunc) << "garbage";
    ProgramBuild again = build_program(ctx, dev, "trace.cl", {});
    EXPECT_FALSE(again.from_cache);
    EXPECT_NO_THROW(cl::Kernel(again.program, "trace_closest"));
}

TEST(ProgramCache, BuildFailureReportsTheLog) {
    ScopedDirEnv kernels("TESSERA_KERNEL_DIR", "broken-kernels");
    ScopedDirEnv cache("TESSERA_CACHE_DIR", "cache-broken");
    std::ofstream(kernels.dir() / "broken.cl") << "__kernel void k(__global float* x) { x[0] = undefined_name; }\n";
    ClDeviceInfo dev = select_cl_device("");
    cl::Context ctx(dev.device);
    try {
        build_program(ctx, dev, "broken.cl", {});
        FAIL() << "expected a build failure";
    } catch (const RuntimeError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("broken.cl"), std::string::npos) << msg;
        EXPECT_NE(msg.find("undefined_name"), std::string::npos) << "build log missing:\n" << msg;
    }
}

}  // namespace
}  // namespace tessera
