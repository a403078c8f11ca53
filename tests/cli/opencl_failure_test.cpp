// OpenCL failures as a user meets them: no platform, a buffer larger than the device
// allows, a launch that fails for resources (injected: PoCL does not fail that way). Each is one clear error line; --backend opencl suggests --backend embree.
// (A kernel build failure is tested in tests/opencl/program_cache_test.cpp.)
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "support/scratch_dir.h"
#include "support/shell.h"

namespace fs = std::filesystem;

namespace {

using tessera::test::CliResult;
using tessera::test::run_shell;
using tessera::test::run_tessera;

const std::string kScene = std::string(TESSERA_TEST_DATA) + "/light.json";
// The ICD loader (ocl-icd) reads the vendor list from OCL_ICD_VENDORS instead of
// /etc/OpenCL/vendors when set: pointing it nowhere leaves no platform at all.
const std::string kNoPlatform = "OCL_ICD_VENDORS=/nonexistent";

class OpenCLFailureCli : public tessera::test::ScratchDirTest {};

TEST_F(OpenCLFailureCli, NoPlatformSuggestsEmbree) {
    const fs::path out = dir_ / "img.exr";
    const CliResult r =
        run_tessera("render " + kScene + " --backend opencl --spp 1 --width 8 --height 8 --out " + out.string(), kNoPlatform);
    EXPECT_NE(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("tessera: error: no OpenCL device found"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("--backend embree"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out));
}

// PoCL lists no device when it cannot write its kernel cache under $HOME (here: under a
// file, so even root cannot): the message says so, and not where HOME is fine.
TEST_F(OpenCLFailureCli, AHomePoclCannotWriteIsNamed) {
    const std::string hint = "PoCL also lists none when it cannot write its cache under HOME (/etc/passwd/x): set "
                             "POCL_CACHE_DIR to a writable directory";
    const std::string env = "env -u POCL_CACHE_DIR -u XDG_CACHE_HOME HOME=/etc/passwd/x";
    const CliResult devices = run_tessera("devices", env);
    // Another ICD (a GPU's driver) lists its devices whatever HOME is: nothing to test.
    if (devices.output.find("[0]") != std::string::npos) GTEST_SKIP() << "a device is listed:\n" << devices.output;
    EXPECT_NE(devices.output.find(hint), std::string::npos) << devices.output;
    const CliResult render =
        run_tessera("render " + kScene + " --backend opencl --spp 1 --width 8 --height 8 --out " +
                        (dir_ / "img.exr").string(), env);
    EXPECT_EQ(render.exit_code, 1) << render.output;
    EXPECT_NE(render.output.find("tessera: error: no OpenCL device found (is an ICD such as pocl-opencl-icd "
                                 "installed?; " + hint + "); use --backend embree"),
              std::string::npos) << render.output;
    const CliResult missing_icd = run_tessera("devices", kNoPlatform);
    EXPECT_EQ(missing_icd.output.find("HOME"), std::string::npos) << missing_icd.output;
}

// POCL_CACHE_DIR where PoCL cannot write: a regular file let PoCL list its device and fail
// the first kernel build (a multi-line build failure naming neither); a path under a file
// made it list none, and the hint said nothing. Both now name POCL_CACHE_DIR and why.
TEST_F(OpenCLFailureCli, AnUnwritablePoclCacheDirIsNamed) {
    std::ofstream(dir_ / "file") << "not a directory";
    const std::string render =
        "render " + kScene + " --backend opencl --spp 1 --width 8 --height 8 --out " + (dir_ / "out" / "img.exr").string();
    const std::string file = (dir_ / "file").string();
    const CliResult r = run_tessera(render, "POCL_CACHE_DIR=" + file);
    // The device chosen is another driver's (a GPU's), which POCL_CACHE_DIR does not
    // concern; or there is no OpenCL here at all.
    if (r.exit_code == 0) GTEST_SKIP() << "not PoCL:\n" << r.output;
    if (run_tessera("devices", kNoPlatform).output == run_tessera("devices").output)
        GTEST_SKIP() << "no OpenCL platform here";
    // PoCL may list its device (the error when it is chosen) or none (the no-device hint).
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("POCL_CACHE_DIR=" + file + ": " + file + " is not a directory"), std::string::npos)
        << r.output;
    const CliResult under = run_tessera(render, "POCL_CACHE_DIR=" + file + "/sub");
    EXPECT_EQ(under.exit_code, 1) << under.output;
    EXPECT_NE(under.output.find("POCL_CACHE_DIR=" + file + "/sub: " + file + " is not a directory"), std::string::npos)
        << under.output;
    EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(OpenCLFailureCli, NoPlatformStillRendersWithEmbree) {
    const fs::path out = dir_ / "img.exr";
    const CliResult r =
        run_tessera("render " + kScene + " --backend embree --spp 1 --width 8 --height 8 --out " + out.string(), kNoPlatform);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(fs::exists(out));
}

TEST_F(OpenCLFailureCli, NoPlatformDevicesCommandSaysSo) {
    const CliResult r = run_tessera("devices", kNoPlatform);
    EXPECT_NE(r.output.find("no OpenCL"), std::string::npos) << r.output;
}

TEST_F(OpenCLFailureCli, BufferLargerThanTheDeviceAllows) {
    const fs::path out = dir_ / "img.exr";
    // 64 bytes: less than the scene's BVH node buffer (128 bytes per node).
    const CliResult r = run_tessera("render " + kScene + " --backend opencl --spp 1 --width 8 --height 8 --out " + out.string(),
                                    "TESSERA_CL_MAX_ALLOC=64");
    EXPECT_NE(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("tessera: error: OpenCL: the "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("allows in one allocation (64)"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("--backend embree"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out));
}

TEST_F(OpenCLFailureCli, OutputBufferLargerThanTheDeviceAllows) {
    const fs::path out = dir_ / "img.exr";
    // Scene buffers fit in 1 MiB; a 1024 x 1024 pass output (40 bytes a pixel) does not.
    const CliResult r = run_tessera("render " + kScene + " --backend opencl --spp 1 --width 1024 --height 1024 --out " + out.string(),
                                    "TESSERA_CL_MAX_ALLOC=1048576");
    EXPECT_NE(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("the output buffer needs"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out));
}

// A display watchdog or exhausted resources surface as CL_OUT_OF_RESOURCES from the
// launch or the wait after it; TESSERA_CL_FAIL_LAUNCH injects that error code after the
// first tile (host/opencl/launch.h). The message names the kernel, the device, the
// error and the likely causes with their numbers.
TEST_F(OpenCLFailureCli, LaunchOutOfResourcesNamesKernelDeviceAndCauses) {
    const fs::path out = dir_ / "img.exr";
    const CliResult dev = run_tessera("devices");
    const CliResult r = run_tessera("render " + kScene + " --method direct --backend opencl --spp 1 --width 8 --height 8 --out " +
                                        out.string(),
                                    "TESSERA_CL_FAIL_LAUNCH=-5");
    EXPECT_NE(r.exit_code, 0) << r.output;
    for (const char* part : {"tessera: error: OpenCL kernel direct_pass on ", "CL_OUT_OF_RESOURCES (-5) from clFinish",
                             "watchdog", "TESSERA_CL_LAUNCH_MS", "CL_KERNEL_PRIVATE_MEM_SIZE", "device memory",
                             "--backend embree"})
        EXPECT_NE(r.output.find(part), std::string::npos) << "missing \"" << part << "\" in: " << r.output;
    // The device named is the one rendering: its name appears in `tessera devices`.
    const size_t kernel = r.output.find("OpenCL kernel direct_pass");
    ASSERT_NE(kernel, std::string::npos);
    const size_t on = r.output.find(" on ", kernel), failed = r.output.find(" failed:", kernel);
    ASSERT_NE(on, std::string::npos);
    ASSERT_NE(failed, std::string::npos);
    const std::string device = r.output.substr(on + 4, failed - on - 4);
    EXPECT_FALSE(device.empty());
    EXPECT_NE(dev.output.find(device), std::string::npos) << device << " not in: " << dev.output;
    EXPECT_FALSE(fs::exists(out));
}

TEST_F(OpenCLFailureCli, BadLaunchBudgetIsNamed) {
    const fs::path out = dir_ / "img.exr";
    const CliResult r = run_tessera("render " + kScene + " --backend opencl --spp 1 --width 8 --height 8 --out " + out.string(),
                                    "TESSERA_CL_LAUNCH_MS=fast");
    EXPECT_NE(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("tessera: error: TESSERA_CL_LAUNCH_MS=fast: expected a number"), std::string::npos)
        << r.output;
}

TEST_F(OpenCLFailureCli, BadImportanceChunkIsNamed) {
    const fs::path out = dir_ / "img.exr";
    for (const char* env : {"TESSERA_CL_IMPORTANCE_CHUNK=2.5", "TESSERA_CL_IMPORTANCE_CHUNK=99999999"}) {
        const CliResult r = run_tessera(
            "render " + kScene + " --backend opencl --spp 1 --width 8 --height 8 --out " + out.string(), env);
        EXPECT_NE(r.exit_code, 0) << r.output;
        EXPECT_NE(r.output.find(std::string("tessera: error: ") + env + ": expected a"), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(out));
    }
}

// The on/off switches, the allocation cap and the injected error code take only what they document: "off" or
// "false" was read as on, and a cap of "1kB" as no cap, without a word.
TEST_F(OpenCLFailureCli, BadSwitchOrAllocationCapIsNamed) {
    const fs::path out = dir_ / "img.exr";
    for (const auto& [backend, env, message] :
         {std::tuple{"opencl", "TESSERA_CL_PACKETS=off", "TESSERA_CL_PACKETS=off: expected 0 or 1"},
          std::tuple{"opencl", "TESSERA_CL_GPU=yes", "TESSERA_CL_GPU=yes: expected 0 or 1"},
          std::tuple{"opencl", "TESSERA_CL_LIGHT_PATHS=2", "TESSERA_CL_LIGHT_PATHS=2: expected 0 or 1"},
          std::tuple{"embree", "TESSERA_EMBREE_PACKETS=false", "TESSERA_EMBREE_PACKETS=false: expected 0 or 1"},
          std::tuple{"opencl", "TESSERA_CL_MAX_ALLOC=1kB", "TESSERA_CL_MAX_ALLOC=1kB: expected a whole number of bytes"},
          std::tuple{"opencl", "TESSERA_CL_MAX_ALLOC=-1", "TESSERA_CL_MAX_ALLOC=-1: expected a whole number of bytes"},
          // atoi read "-5x" as -5 and "oom" as 0 (no failure injected), without a word.
          std::tuple{"opencl", "TESSERA_CL_FAIL_LAUNCH=-5x", "TESSERA_CL_FAIL_LAUNCH=-5x: expected an OpenCL error code"},
          std::tuple{"opencl", "TESSERA_CL_FAIL_LAUNCH=oom", "TESSERA_CL_FAIL_LAUNCH=oom: expected an OpenCL error code"},
          std::tuple{"opencl", "TESSERA_CL_FAIL_LAUNCH=5", "TESSERA_CL_FAIL_LAUNCH=5: expected an OpenCL error code"}}) {
        const CliResult r = run_tessera("render " + kScene + " --backend " + backend +
                                            " --spp 1 --width 8 --height 8 --out " + out.string(),
                                        env);
        EXPECT_EQ(r.exit_code, 2) << env << ": " << r.output;
        EXPECT_NE(r.output.find(std::string("tessera: error: ") + message), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(out));
    }
    // A device index too long for a number is out of range, said as such (it was "stoul").
    const CliResult r = run_tessera("render " + kScene + " --backend opencl --device 99999999999999999999 --spp 1 "
                                    "--width 8 --height 8 --out " + out.string());
    EXPECT_NE(r.output.find("--device 99999999999999999999: no such OpenCL device"), std::string::npos) << r.output;
}

}  // namespace
