// `tessera render` interrupted by SIGINT: exit 130 with a checkpoint and no image;
// `--resume` then finishes it and removes the checkpoint; a resume with other settings
// or without a checkpoint is refused naming the setting or the expected file.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/scratch_dir.h"
#include "support/shell.h"

namespace fs = std::filesystem;

namespace {

using CliRun = tessera::test::CliResult;

/// Runs tessera with `args`, stdout and stderr into one pipe, in a process group of its
/// own. If `interrupt_on` is not empty, sends SIGINT once that text has appeared in the
/// output; with `group_too`, at once a second one to the process group, as `timeout -s
/// INT` and a terminal's Ctrl-C do.
CliRun run_tessera(const std::vector<std::string>& args, const std::string& interrupt_on = "", bool group_too = false) {
    std::vector<std::string> words{TESSERA_EXE};
    words.insert(words.end(), args.begin(), args.end());
    bool sent = false;
    return tessera::test::run_watched(words, true, [&](pid_t pid, const std::string& out) {
        if (interrupt_on.empty() || sent || out.find(interrupt_on) == std::string::npos) return;
        ::kill(pid, SIGINT);
        if (group_too) ::kill(-pid, SIGINT);
        sent = true;
    });
}

class CheckpointCli : public tessera::test::ScratchDirTest {
protected:

    std::vector<std::string> render_args(const std::vector<std::string>& extra) const {
        // Slow enough (50 passes of ~30 ms on two cores) that SIGINT arrives mid-render;
        // the method named, so the test does not change with the CLI's default.
        std::vector<std::string> a{"render",  "--method", "direct", "--backend", "embree", "--spp", "50", "--width", "96",
                                   "--height", "96", "--shadow-samples", "48", "--out", (dir_ / "img.exr").string()};
        a.insert(a.end(), extra.begin(), extra.end());
        return a;
    }
};

// A --frames sequence interrupted in frame 1 keeps frame 0, which it finished, and says
// how to continue; frames 1 and 2 are not written, and no temporary is left. (Before, an
// interrupted sequence wrote no frame, and a long animation stopped late lost them all.)
TEST_F(CheckpointCli, AnInterruptedSequenceKeepsTheFramesItFinished) {
    const std::vector<std::string> args{"render", std::string(TESSERA_SCENES_DIR) + "/cornell-box-animated.json",
                                        "--method", "direct", "--backend", "embree", "--spp", "50", "--width", "96",
                                        "--height", "96", "--shadow-samples", "48", "--frames", "0:2", "--out",
                                        (dir_ / "seq.exr").string()};
    CliRun r = run_tessera(args, "tessera: frame 0:");
    ASSERT_EQ(r.exit_code, 130) << r.output;
    EXPECT_NE(r.output.find("frames 0..0 are written, continue with --frames 1:2"), std::string::npos) << r.output;
    EXPECT_GT(fs::file_size(dir_ / "seq.0000.exr"), 0u);
    EXPECT_GT(fs::file_size(dir_ / "seq.0000.png"), 0u);
    EXPECT_FALSE(fs::exists(dir_ / "seq.0001.exr"));
    EXPECT_FALSE(fs::exists(dir_ / "seq.0002.exr"));
    size_t files = 0;
    for (const auto& e : fs::directory_iterator(dir_)) files += e.is_regular_file();
    EXPECT_EQ(files, 2u) << "frame 0's EXR and PNG, no temporary";
}

TEST_F(CheckpointCli, InterruptThenResume) {
    const fs::path exr = dir_ / "img.exr", png = dir_ / "img.png", ckpt = dir_ / "img.ckpt";
    CliRun r = run_tessera(render_args({}), "/50 spp");
    ASSERT_EQ(r.exit_code, 130) << r.output;
    EXPECT_NE(r.output.find("tessera: interrupted after "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(" of 50 spp"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("resume with --resume"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(ckpt.string()), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(ckpt));
    EXPECT_FALSE(fs::exists(exr));
    EXPECT_FALSE(fs::exists(png));

    CliRun bad = run_tessera(render_args({"--resume", "--seed", "2"}));
    EXPECT_EQ(bad.exit_code, 2) << bad.output;
    EXPECT_NE(bad.output.find("tessera: error: checkpoint " + ckpt.string()), std::string::npos) << bad.output;
    EXPECT_NE(bad.output.find("--seed 1, this run has --seed 2"), std::string::npos) << bad.output;
    EXPECT_TRUE(fs::exists(ckpt));
    EXPECT_FALSE(fs::exists(exr));

    // The same command without --resume would replace the saved passes: refused.
    const std::string saved = tessera::test::file_bytes(ckpt);
    CliRun again = run_tessera(render_args({}));
    EXPECT_EQ(again.exit_code, 2) << again.output;
    EXPECT_NE(again.output.find("tessera: error: --out " + exr.string() + ": the checkpoint of an interrupted render "
                                "is beside it, " + ckpt.string() + ": continue it with --resume, or remove it to "
                                "start over"),
              std::string::npos) << again.output;
    EXPECT_EQ(tessera::test::file_bytes(ckpt), saved);
    EXPECT_FALSE(fs::exists(exr));

    CliRun done = run_tessera(render_args({"--resume"}));
    ASSERT_EQ(done.exit_code, 0) << done.output;
    EXPECT_NE(done.output.find("50/50 spp"), std::string::npos) << done.output;
    EXPECT_GT(fs::file_size(exr), 0u);
    EXPECT_GT(fs::file_size(png), 0u);
    EXPECT_FALSE(fs::exists(ckpt));
}

// Two SIGINTs back to back (they once killed the render with no checkpoint):
// the second is ignored, the first leaves a checkpoint that --resume finishes. Sent on
// the line printed just before the first pass, or on the first progress line.
TEST_F(CheckpointCli, TwoSignalsAtOnceStillLeaveACheckpoint) {
    const fs::path ckpt = dir_ / "img.ckpt";
    const std::vector<std::string> args = {"render", "--backend", "embree", "--spp", "20", "--width", "96", "--height",
                                           "96", "--shadow-samples", "48", "--out", (dir_ / "img.exr").string()};
    for (int run = 0; run < 4; ++run) {
        SCOPED_TRACE(run);
        const CliRun r = run_tessera(args, run % 2 ? "/20 spp" : " triangles", true);
        ASSERT_EQ(r.exit_code, 130) << r.output;
        const bool none = r.output.find("no checkpoint written") != std::string::npos;
        // Sent on a progress line, a pass has ended: there must be a checkpoint.
        if (run % 2) {
            EXPECT_FALSE(none) << r.output;
        }
        if (none) {
            // Before the first pass ended: said so, and nothing on disk.
            EXPECT_NE(r.output.find("tessera: interrupted before the first pass; no checkpoint written"),
                      std::string::npos) << r.output;
            EXPECT_FALSE(fs::exists(ckpt));
            continue;
        }
        EXPECT_NE(r.output.find("of 20 spp; checkpoint saved to " + ckpt.string() + "; resume with --resume"),
                  std::string::npos) << r.output;
        std::vector<std::string> resume = args;
        resume.push_back("--resume");
        const CliRun done = run_tessera(resume);
        ASSERT_EQ(done.exit_code, 0) << done.output;
        EXPECT_NE(done.output.find("20/20 spp"), std::string::npos) << done.output;
        EXPECT_FALSE(fs::exists(ckpt));
        EXPECT_GT(fs::file_size(dir_ / "img.exr"), 0u);
        fs::remove(dir_ / "img.exr");
        fs::remove(dir_ / "img.png");
    }
}

// tic keeps no checkpoint (it would not hold the cache, and --resume is refused): an
// interrupted tic render says so and leaves no file, rather than pointing at --resume.
TEST_F(CheckpointCli, InterruptedTicLeavesNoCheckpoint) {
    const fs::path ckpt = dir_ / "img.ckpt";
    std::vector<std::string> args = render_args({});
    args[2] = "tic";
    const CliRun r = run_tessera(args, "/50 spp");
    ASSERT_EQ(r.exit_code, 130) << r.output;
    EXPECT_NE(r.output.find("spp (tic keeps no checkpoint); no checkpoint written"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("--resume"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(ckpt));
    EXPECT_FALSE(fs::exists(dir_ / "img.exr"));
    // An interval given for it is ignored, saying so, and still no checkpoint is written.
    args[6] = "2";  // --spp
    args.insert(args.end(), {"--checkpoint-interval", "1e-9"});
    const CliRun ok = run_tessera(args);
    ASSERT_EQ(ok.exit_code, 0) << ok.output;
    EXPECT_NE(ok.output.find("--checkpoint-interval: --method tic keeps no checkpoint"), std::string::npos) << ok.output;
    EXPECT_FALSE(fs::exists(ckpt));
}

// Outputs that cannot be written when the render ends (here the PNG's path became a
// directory mid-run): no image is written, and the periodic checkpoint is kept, said with
// what to do, so the passes are not lost; --resume then finishes once the path is free.
TEST_F(CheckpointCli, AFailedImageWriteKeepsThePeriodicCheckpoint) {
    const fs::path exr = dir_ / "img.exr", png = dir_ / "img.png", ckpt = dir_ / "img.ckpt";
    const std::vector<std::string> args = render_args({"--checkpoint-interval", "1e-9"});
    std::vector<std::string> words{TESSERA_EXE};
    words.insert(words.end(), args.begin(), args.end());
    bool blocked = false;
    const CliRun r = tessera::test::run_watched(words, true, [&](pid_t, const std::string& out) {
        // After the first pass's checkpoint, well before the last of 50 passes.
        if (blocked || out.find("/50 spp") == std::string::npos) return;
        fs::create_directories(png / "in-the-way");
        blocked = true;
    });
    ASSERT_TRUE(blocked) << r.output;
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("the render's checkpoint " + ckpt.string() +
                            " is kept (the passes to its last save): once the outputs can be written, add --resume"),
              std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(ckpt));
    EXPECT_FALSE(fs::exists(exr));
    size_t files = 0;
    for (const auto& e : fs::directory_iterator(dir_)) files += e.is_regular_file();
    EXPECT_EQ(files, 1u) << "the checkpoint, no temporary";

    fs::remove_all(png);
    const CliRun done = run_tessera(render_args({"--resume"}));
    ASSERT_EQ(done.exit_code, 0) << done.output;
    EXPECT_GT(fs::file_size(exr), 0u);
    EXPECT_GT(fs::file_size(png), 0u);
    EXPECT_FALSE(fs::exists(ckpt));
}

TEST_F(CheckpointCli, ResumeWithoutCheckpointNamesTheExpectedFile) {
    CliRun r = run_tessera(render_args({"--resume"}));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--resume: no checkpoint " + (dir_ / "img.ckpt").string()), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "img.exr"));
}

TEST_F(CheckpointCli, CorruptCheckpointIsRefusedNamingIt) {
    { std::FILE* f = std::fopen((dir_ / "img.ckpt").c_str(), "wb"); std::fputs("TSCKPT01 junk", f); std::fclose(f); }
    CliRun r = run_tessera(render_args({"--resume"}));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("checkpoint " + (dir_ / "img.ckpt").string()), std::string::npos) << r.output;
    // Before the scene's banner and the backend's set-up (it came after them).
    EXPECT_EQ(r.output.find(" triangles"), std::string::npos) << r.output;
}

TEST_F(CheckpointCli, NegativeIntervalIsRejected) {
    CliRun r = run_tessera(render_args({"--checkpoint-interval", "-1"}));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--checkpoint-interval"), std::string::npos) << r.output;
}

}  // namespace
