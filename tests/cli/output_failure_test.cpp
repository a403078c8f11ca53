// Output to a full or read-only file system: `tessera render` fails with one clear
// error line naming the path, and an image already there stays as it was (the writer
// writes a temporary file in the target directory and renames it over the target only
// once complete; host/image/atomic_file.h).
//
// Both need a small file system of their own: a 64 KiB tmpfs, mounted in a private
// mount namespace (unshare -m) so nothing leaks to the host. Where that is not allowed
// (no CAP_SYS_ADMIN, e.g. unprivileged CI), the tests skip; the same paths are covered
// without mounts by tests/image/image_io_test.cpp (a failing write callback keeps the
// target; a read-only directory, when not root).
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "support/scratch_dir.h"

namespace fs = std::filesystem;

namespace {

class OutputFailureCli : public tessera::test::ScratchDirTest {
protected:
    // Runs `setup` (shell, with $M the mount point) on a fresh 64 KiB tmpfs in a private
    // mount namespace, then renders to $M/img.exr; records the exit status, the output,
    // the old image's contents afterwards and the directory listing. False: no mounts.
    bool render_on_tmpfs(const std::string& setup,
                         const std::string& scene = std::string(TESSERA_TEST_DATA) + "/light.json",
                         const std::string& more = "") {
        const fs::path m = dir_ / "mnt";
        fs::create_directories(m);
        const std::string render = std::string(TESSERA_EXE) + " render " + scene +
                                   " --backend embree --spp 1 --width 64 --height 64 --out $M/img.exr" + more;
        const std::string script = "set -u; M='" + m.string() + "'; R='" + dir_.string() + "'; " +
                                   "mount -t tmpfs -o size=64k tmpfs $M || exit 99; " +
                                   "printf KEEP > $M/img.exr; printf KEEP > $M/img.png; " + setup + "; " +
                                   render + " > $R/out.txt 2>&1; echo $? > $R/status.txt; " +
                                   "cat $M/img.exr > $R/exr.txt; cat $M/img.png > $R/png.txt; ls -A $M > $R/ls.txt";
        std::ofstream(dir_ / "run.sh") << script << "\n";
        const std::string cmd = "unshare --mount --propagation private sh " + (dir_ / "run.sh").string() + " > /dev/null 2>&1";
        const int rc = std::system(cmd.c_str());
        return WIFEXITED(rc) && WEXITSTATUS(rc) != 99 && fs::exists(dir_ / "status.txt");
    }

    void expect_failed_and_kept(const std::string& what) {
        const std::string out = tessera::test::file_bytes(dir_ / "out.txt");
        EXPECT_NE(std::stoi(tessera::test::file_bytes(dir_ / "status.txt")), 0) << out;
        EXPECT_NE(out.find("tessera: error:"), std::string::npos) << out;
        EXPECT_NE(out.find("img."), std::string::npos) << "the message should name the file: " << out;
        EXPECT_EQ(tessera::test::file_bytes(dir_ / "exr.txt"), "KEEP") << what << ": the existing EXR was damaged";
        EXPECT_EQ(tessera::test::file_bytes(dir_ / "png.txt"), "KEEP") << what << ": the existing PNG was damaged";
        // Nothing but the two old files (and the filler) remains: no temporary file.
        std::istringstream ls(tessera::test::file_bytes(dir_ / "ls.txt"));
        for (std::string name; std::getline(ls, name);)
            EXPECT_TRUE(name == "img.exr" || name == "img.png" || name == "filler") << "left behind: " << name;
    }
};

TEST_F(OutputFailureCli, FullFileSystemKeepsTheExistingImage) {
    // Fill the tmpfs: a 64 x 64 EXR (about 50 KiB with its variance channels) cannot fit.
    if (!render_on_tmpfs("dd if=/dev/zero of=$M/filler bs=1k count=200 2>/dev/null || true"))
        GTEST_SKIP() << "cannot mount a tmpfs in a private mount namespace here";
    expect_failed_and_kept("full");
    EXPECT_NE(tessera::test::file_bytes(dir_ / "out.txt").find("No space left on device"), std::string::npos) << tessera::test::file_bytes(dir_ / "out.txt");
}

// A --frames run writes a frame's files while the next renders (image/background_writer.h):
// the tmpfs holds frame 0 (a 64 x 64 EXR of about 50 KiB and its PNG), not frame 1, whose
// write fails on the worker thread. The run still stops with the error naming that frame's
// file, and leaves no frame and no temporary, frame 0's included (docs: README, "written
// as one unit").
TEST_F(OutputFailureCli, AFullFileSystemMidSequenceLeavesNoFrame) {
    if (!render_on_tmpfs("true", std::string(TESSERA_SCENES_DIR) + "/cornell-box-animated.json",
                         " --method igi --frames 0:5"))
        GTEST_SKIP() << "cannot mount a tmpfs in a private mount namespace here";
    expect_failed_and_kept("full in a sequence");
    const std::string out = tessera::test::file_bytes(dir_ / "out.txt");
    EXPECT_NE(out.find("No space left on device"), std::string::npos) << out;
    EXPECT_NE(out.find("img.000"), std::string::npos) << "the message should name the frame's file: " << out;
}

TEST_F(OutputFailureCli, ReadOnlyFileSystemKeepsTheExistingImage) {
    // A read-only mount stops root too (unlike directory permissions).
    if (!render_on_tmpfs("mount -o remount,ro $M"))
        GTEST_SKIP() << "cannot mount a tmpfs in a private mount namespace here";
    expect_failed_and_kept("read-only");
    EXPECT_NE(tessera::test::file_bytes(dir_ / "out.txt").find("Read-only file system"), std::string::npos) << tessera::test::file_bytes(dir_ / "out.txt");
}

}  // namespace
