// Kernels that build and give the same images with optimisation off (README.md, TESSERA_CL_OPTIONS): drivers
// that do not inline (clang-based ones, or any build at -cl-opt-disable) need every
// shared function to have a definition they can link (TS_INLINE is `static inline` in
// OpenCL C, kernels/shared/compat.h), and unoptimised code must round as optimised code
// does (no fast-math, FP_CONTRACT off). TESSERA_CL_OPTIONS adds build options
// (host/opencl/program_cache.cpp); the program cache keys on them, so both builds are
// real. Every program (direct.cl, pt.cl, igi.cl with its media and AIS kernels, ic.cl)
// must render the same bytes with and without -cl-opt-disable.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "support/scratch_dir.h"
#include "support/shell.h"

namespace fs = std::filesystem;

namespace {

using tessera::test::CliResult;
using tessera::test::run_tessera;

struct Case {
    const char* method;
    const char* scene;
};

class OptDisableCli : public tessera::test::ScratchDirTest, public ::testing::WithParamInterface<Case> {};

TEST_P(OptDisableCli, SameImageWithOptimisationOff) {
    const Case c = GetParam();
    const std::string args = std::string("render ") + TESSERA_SCENES_DIR + "/" + c.scene + " --method " + c.method +
                             " --backend opencl --spp 1 --width 24 --height 24 --vpl-paths 8 --ic-paths 32 --aov";
    const fs::path opt = dir_ / "opt.exr", noopt = dir_ / "noopt.exr";
    const CliResult a = run_tessera(args + " --out " + opt.string());
    ASSERT_EQ(a.exit_code, 0) << a.output;
    const CliResult b = run_tessera(args + " --out " + noopt.string(), "TESSERA_CL_OPTIONS=-cl-opt-disable");
    ASSERT_EQ(b.exit_code, 0) << b.output;
    EXPECT_EQ(tessera::test::file_bytes(opt), tessera::test::file_bytes(noopt)) << c.method << " on " << c.scene;
}

// The GPU variant (TESSERA_CL_GPU=1: per-ray kernels with the short-stack traversal,
// kernels/bvh_short_stack.h) builds and renders the same bytes with optimisation off too.
TEST_F(OptDisableCli, GpuVariantSameImageWithOptimisationOff) {
    const std::string args = std::string("render ") + TESSERA_SCENES_DIR +
                             "/cornell-box-fog.json --method ais --backend opencl --spp 1 --width 24 --height 24 "
                             "--vpl-paths 8 --aov";
    const fs::path opt = dir_ / "opt.exr", noopt = dir_ / "noopt.exr";
    const CliResult a = run_tessera(args + " --out " + opt.string(), "TESSERA_CL_GPU=1");
    ASSERT_EQ(a.exit_code, 0) << a.output;
    ASSERT_NE(a.output.find("short stack"), std::string::npos) << a.output;
    const CliResult b = run_tessera(args + " --out " + noopt.string(), "TESSERA_CL_GPU=1 TESSERA_CL_OPTIONS=-cl-opt-disable");
    ASSERT_EQ(b.exit_code, 0) << b.output;
    EXPECT_EQ(tessera::test::file_bytes(opt), tessera::test::file_bytes(noopt));
}

// The option really reaches the compiler (else the test above could not fail): an
// unknown one fails the build with a message naming it.
class ClOptionsCli : public tessera::test::ScratchDirTest {};

TEST_F(ClOptionsCli, ExtraBuildOptionsReachTheCompiler) {
    const fs::path out = dir_ / "x.exr";
    const CliResult r = run_tessera(std::string("render ") + TESSERA_SCENES_DIR +
                                        "/cornell-box.json --backend opencl --spp 1 --width 8 --height 8 --out " +
                                        out.string(),
                                    "TESSERA_CL_OPTIONS=-cl-no-such-option");
    EXPECT_NE(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("-cl-no-such-option"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out));
}

INSTANTIATE_TEST_SUITE_P(Programs, OptDisableCli,
                         ::testing::Values(Case{"direct", "cornell-box.json"}, Case{"pt", "cornell-box-fog.json"},
                                           Case{"ais", "cornell-box-fog.json"}, Case{"ic", "cornell-box.json"}));

}  // namespace
