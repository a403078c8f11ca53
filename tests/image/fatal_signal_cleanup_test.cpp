// image/fatal_signal_cleanup.h: a process ended by a second signal during a long pass
// leaves none of its outputs' temporaries behind; a registration that ended (the file
// renamed into place or removed by its owner) no longer names the path.
#include "image/fatal_signal_cleanup.h"

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <utility>

#include <gtest/gtest.h>

#include "image/atomic_file.h"
#include "render/interrupt.h"
#include "support/scratch_dir.h"

namespace fs = std::filesystem;

namespace tessera {
namespace {

class FatalSignalCleanup : public test::ScratchDirTest {
protected:
    fs::path touch(const std::string& name) {
        const fs::path p = dir_ / name;
        std::ofstream(p) << "partial";
        return p;
    }
};

// Death tests in the "fast" style while alive: the child forks from here and writes into
// this test's scratch directory ("threadsafe" would re-run SetUp in a new process).
class FastDeathTests {
public:
    FastDeathTests() : style_(GTEST_FLAG_GET(death_test_style)) { GTEST_FLAG_SET(death_test_style, "fast"); }
    ~FastDeathTests() { GTEST_FLAG_SET(death_test_style, style_); }
    FastDeathTests(const FastDeathTests&) = delete;
    FastDeathTests& operator=(const FastDeathTests&) = delete;

private:
    std::string style_;
};

TEST_F(FatalSignalCleanup, RemovesRegisteredFilesOnlyWhileTheyAreRegistered) {
    const fs::path kept = touch(".kept.tmp.1"), taken = touch(".taken.tmp.2"), moved = touch(".moved.tmp.3");
    { const RemovedOnFatalSignal ended(kept); }
    const RemovedOnFatalSignal live(taken);
    RemovedOnFatalSignal first(moved);
    const RemovedOnFatalSignal second(std::move(first));
    EXPECT_TRUE(live.registered());
    EXPECT_FALSE(first.registered());
    EXPECT_TRUE(second.registered());
    remove_registered_temporaries();
    EXPECT_TRUE(fs::exists(kept));
    EXPECT_FALSE(fs::exists(taken));
    EXPECT_FALSE(fs::exists(moved));
}

// Directories registered outermost first go innermost first, and only when empty.
TEST_F(FatalSignalCleanup, RemovesRegisteredDirectoriesThatAreLeftEmpty) {
    const fs::path outer = dir_ / "made", inner = outer / "deeper", kept = dir_ / "holds";
    fs::create_directories(inner);
    fs::create_directories(kept);
    const fs::path temp = touch("made/deeper/.x.exr.tmp.1");
    touch("holds/finished.exr");
    const RemovedOnFatalSignal o = RemovedOnFatalSignal::directory(outer),
                               i = RemovedOnFatalSignal::directory(inner), k = RemovedOnFatalSignal::directory(kept),
                               t(temp);
    remove_registered_temporaries();
    EXPECT_FALSE(fs::exists(outer));
    EXPECT_TRUE(fs::exists(kept / "finished.exr"));
}

// The viewer or `render --frames` holding finished frames in a CommitGroup during a pass
// of several seconds: the first Ctrl-C asks for a clean stop, a second one after the grace
// time ends the process at once. Its temporaries must go with it.
TEST_F(FatalSignalCleanup, ASecondSignalLeavesNoTemporaryBehind) {
    // SIGTERM, not SIGINT: a test run in the background of a script inherits an ignored
    // SIGINT, which InterruptScope keeps ignored.
    const FastDeathTests fast;
    const fs::path out = dir_ / "frames" / "frame.0001.exr";  // the directory is the run's too
    EXPECT_EXIT(
        {
            const InterruptScope interrupts;
            CommitGroup outputs;
            std::ofstream(outputs.add(out)) << "finished frame";
            ::raise(SIGTERM);  // recorded: the pass goes on
            std::this_thread::sleep_for(std::chrono::duration<double>(kInterruptGraceSeconds + 0.2));
            ::raise(SIGTERM);  // ends the process here
            std::_Exit(0);
        },
        ::testing::KilledBySignal(SIGTERM), "no checkpoint written");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), {}), 0);
}

// `tessera compare` has no clean stop: one signal ends it, without the maps' temporaries
// or the directories made for them.
TEST_F(FatalSignalCleanup, OneSignalEndsACommandWithoutItsTemporaries) {
    const FastDeathTests fast;
    EXPECT_EXIT(
        {
            ::signal(SIGTERM, SIG_DFL);
            const TemporariesRemovedOnSignal on_signal;
            CommitGroup maps;
            std::ofstream(maps.add(dir_ / "maps" / "flip.png")) << "half a map";
            ::raise(SIGTERM);
            std::_Exit(0);
        },
        ::testing::KilledBySignal(SIGTERM), "");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), {}), 0);
}

// A signal during a commit (SignalsHeld) waits for it: the process ends after the files
// landed, not between them.
TEST_F(FatalSignalCleanup, ASignalDuringAHoldEndsTheProcessAfterIt) {
    const FastDeathTests fast;
    EXPECT_EXIT(
        {
            ::signal(SIGTERM, SIG_DFL);
            const TemporariesRemovedOnSignal on_signal;
            std::ofstream(dir_ / "a.png") << "old a";  // replaced: the commit keeps it aside meanwhile
            CommitGroup maps;
            std::ofstream(maps.add(dir_ / "a.png")) << "a";
            std::ofstream(maps.add(dir_ / "b.png")) << "b";
            {
                const SignalsHeld whole;
                ::raise(SIGTERM);  // held
                maps.commit();
                std::ofstream(dir_ / "after-commit") << "still running";
            }
            std::ofstream(dir_ / "after-hold") << "must not be written";
            std::_Exit(0);
        },
        ::testing::KilledBySignal(SIGTERM), "");
    EXPECT_EQ(test::file_bytes(dir_ / "a.png"), "a");
    EXPECT_EQ(test::file_bytes(dir_ / "b.png"), "b");
    EXPECT_TRUE(fs::exists(dir_ / "after-commit"));
    EXPECT_FALSE(fs::exists(dir_ / "after-hold"));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), {}), 3) << "a.png, b.png, after-commit: no backup left";
}

// A signal ignored on entry (nohup, a background job) stays ignored, and the old
// handler is back at the scope's end.
TEST_F(FatalSignalCleanup, ASignalIgnoredOnEntryStaysIgnored) {
    struct sigaction ignore {}, old {}, during {}, after {};
    ignore.sa_handler = SIG_IGN;
    sigaction(SIGHUP, &ignore, &old);
    {
        const TemporariesRemovedOnSignal on_signal;
        sigaction(SIGHUP, nullptr, &during);
        ::raise(SIGHUP);  // ignored: the test goes on
    }
    sigaction(SIGHUP, &old, &after);
    EXPECT_EQ(during.sa_handler, SIG_IGN);
    EXPECT_EQ(after.sa_handler, SIG_IGN);
}

}  // namespace
}  // namespace tessera
