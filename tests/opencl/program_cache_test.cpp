// OpenCL programs: include expansion, the on-disk binary cache, build-log reporting.
#include "opencl/program_cache.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "opencl/kernel_source.h"
#include "support/scoped_env.h"
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

// An entry that is whole in form but not in content (cut short by a crash: PoCL crashed
// on it; bytes flipped: the launch failed; another program's entry under this name: the
// kernel was missing) is rebuilt and replaced, every case, before the driver sees it.
TEST(ProgramCache, DamagedOrForeignEntryIsRebuiltAndReplaced) {
    ScopedDirEnv cache("TESSERA_CACHE_DIR", "cache-damaged");
    ClDeviceInfo dev = select_cl_device("");
    cl::Context ctx(dev.device);
    build_program(ctx, dev, "trace.cl", {});
    build_program(ctx, dev, "direct.cl", {});
    fs::path trace, direct;
    for (const auto& e : fs::directory_iterator(cache.dir()))
        (e.path().filename().string().rfind("trace.cl", 0) == 0 ? trace : direct) = e.path();
    ASSERT_FALSE(trace.empty() || direct.empty());
    const auto bytes = [](const fs::path& p) {
        std::ifstream in(p, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    const std::string good = bytes(trace);
    std::string flipped = good;
    for (size_t i = 100; i < flipped.size(); i += 97) flipped[i] ^= 0x55;
    for (const std::string& damaged : {good.substr(0, good.size() / 4), good.substr(0, 200), flipped, bytes(direct)}) {
        std::ofstream(trace, std::ios::binary | std::ios::trunc) << damaged;
        const ProgramBuild again = build_program(ctx, dev, "trace.cl", {});
        EXPECT_FALSE(again.from_cache) << damaged.size() << " bytes";
        EXPECT_NO_THROW(cl::Kernel(again.program, "trace_closest"));
        EXPECT_TRUE(build_program(ctx, dev, "trace.cl", {}).from_cache) << "the entry is replaced by the rebuilt one";
    }
}

// Without $TESSERA_CACHE_DIR, $XDG_CACHE_HOME and $HOME the cache is a per-user directory
// in $TMPDIR, private (an older build's 0755 one is made 0700), and none at all where it
// is not ours: a link to elsewhere (another user's planted binary would be run).
TEST(ProgramCache, TemporaryFallbackIsPrivateToTheUser) {
    ScopedDirEnv tmp("TMPDIR", "cache-tmpdir");
    const test::ScopedEnv no_cache("TESSERA_CACHE_DIR", nullptr), no_xdg("XDG_CACHE_HOME", nullptr),
        no_home("HOME", nullptr);
    const fs::path expected = tmp.dir() / ("tessera-cache-" + std::to_string(::geteuid()));
    EXPECT_EQ(program_cache_dir(), expected);
    const auto mode = [&] { return fs::status(expected).permissions() & fs::perms::mask; };
    EXPECT_EQ(mode(), fs::perms::owner_all);
    fs::permissions(expected, fs::perms::all);
    EXPECT_EQ(program_cache_dir(), expected);
    EXPECT_EQ(mode(), fs::perms::owner_all) << "made private again";
    fs::remove_all(expected);
    fs::create_directories(tmp.dir() / "elsewhere");
    fs::create_directory_symlink(tmp.dir() / "elsewhere", expected);
    EXPECT_EQ(program_cache_dir(), fs::path()) << "a link is not the user's own directory";
}

TEST(ProgramCache, BuildFailureReportsTheLog) {
    ScopedDirEnv kernels("TESSERA_KERNEL_DIR", "broken-kernels");
    ScopedDirEnv cache("TESSERA_CACHE_DIR", "cache-broken");
    std::ofstream(kernels.dir() / "broken.cl") << "#warning no errors here\n"
                                                  "__kernel void k(__global float* x) { x[0] = undefined_name; }\n";
    ClDeviceInfo dev = select_cl_device("");
    cl::Context ctx(dev.device);
    try {
        build_program(ctx, dev, "broken.cl", {});
        FAIL() << "expected a build failure";
    } catch (const RuntimeError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("broken.cl"), std::string::npos) << msg;
        EXPECT_NE(msg.find("undefined_name"), std::string::npos) << "build log missing:\n" << msg;
        // The first line names the error where it is: the file as the user knows it and its
        // own line (the expanded source's #line markers), not the driver's temporary file.
        const std::string first = msg.substr(0, msg.find('\n'));
        EXPECT_NE(first.find("kernels/broken.cl:2:"), std::string::npos) << first;
        EXPECT_NE(first.find("undefined_name"), std::string::npos) << first;
    }
}

// PoCL lists errors first; another driver may put a warning first, whose text can say
// "errors": the line in clang's "error:" form is the one the message leads with.
TEST(ProgramCache, FirstErrorOfABuildLog) {
    EXPECT_EQ(build_log_first_error("warning: a.cl:1:2: no errors here\n  a.cl:2:5: error: use of undeclared x \n"),
              "a.cl:2:5: error: use of undeclared x");
    EXPECT_EQ(build_log_first_error("Device X failed: 3 errors\n"), "Device X failed: 3 errors");
    EXPECT_EQ(build_log_first_error("warning: unused\n"), "");
    EXPECT_EQ(build_log_first_error(""), "");
}

// An error in an included header is reported at that header's own line.
TEST(ProgramCache, BuildErrorNamesTheIncludedHeaderAndItsLine) {
    ScopedDirEnv kernels("TESSERA_KERNEL_DIR", "broken-header");
    ScopedDirEnv cache("TESSERA_CACHE_DIR", "cache-broken-header");
    std::ofstream(kernels.dir() / "fine.h") << "#define FINE 1\n";
    std::ofstream(kernels.dir() / "bad.h") << "#include \"fine.h\"\n\nfloat f(void) { return missing_name; }\n";
    std::ofstream(kernels.dir() / "main.cl") << "#include \"fine.h\"\n#include \"bad.h\"\n\n__kernel void k(__global float* "
                                                "x) { x[0] = f() + no_such; }\n";
    ClDeviceInfo dev = select_cl_device("");
    cl::Context ctx(dev.device);
    try {
        build_program(ctx, dev, "main.cl", {});
        FAIL() << "expected a build failure";
    } catch (const RuntimeError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("kernels/bad.h:3:"), std::string::npos) << msg;
        EXPECT_NE(msg.find("kernels/main.cl:4:"), std::string::npos) << msg;
    }
}

TEST(ProgramCache, CorrectlyRoundedDivisionWhereTheDeviceHasIt) {
    // The traversal's box bound assumes it (kernels/bvh_traverse.h); a device without it
    // gets the widened bound instead. Both variants build, and their traversals agree.
    ScopedDirEnv cache("TESSERA_CACHE_DIR", "cache-rounding");
    ClDeviceInfo dev = select_cl_device("");
    cl::Context ctx(dev.device);
    const ProgramBuild b = build_program(ctx, dev, "trace.cl", {});
    const bool flag = b.options.find("-cl-fp32-correctly-rounded-divide-sqrt") != std::string::npos;
    const bool widened = b.options.find("-DTS_INEXACT_DIV_SQRT") != std::string::npos;
    EXPECT_EQ(flag, dev.correctly_rounded_div_sqrt) << b.options;
    EXPECT_NE(flag, widened) << b.options;
    dev.correctly_rounded_div_sqrt = !dev.correctly_rounded_div_sqrt;
    const ProgramBuild other = build_program(ctx, dev, "trace.cl", {});
    EXPECT_NE(other.options, b.options);
    EXPECT_NO_THROW(cl::Kernel(other.program, "trace_occluded"));
}

TEST(KernelLimits, AWorkGroupOverTheDeviceLimitNamesKernelDeviceAndSizes) {
    EXPECT_EQ(kernel_limit_problem("igi_surface_pass", "GPU X", 256, 64), "");
    EXPECT_EQ(kernel_limit_problem("igi_surface_pass", "GPU X", 64, 64), "");
    const std::string msg = kernel_limit_problem("igi_surface_pass", "GPU X", 32, 64);
    for (const char* part : {"igi_surface_pass", "GPU X", "32", "64", "TS_WORKGROUP_SIZE"})
        EXPECT_NE(msg.find(part), std::string::npos) << part << " missing: " << msg;
}

TEST(KernelLimits, EveryKernelFitsOnTheTestDevice) {
    ScopedDirEnv cache("TESSERA_CACHE_DIR", "cache-limits");
    ClDeviceInfo dev = select_cl_device("");
    cl::Context ctx(dev.device);
    const ProgramBuild b = build_program(ctx, dev, "trace.cl", {});
    for (const char* name : {"trace_closest", "trace_occluded"})
        EXPECT_NO_THROW(check_kernel_limits(cl::Kernel(b.program, name), dev, name));
}

}  // namespace
}  // namespace tessera
