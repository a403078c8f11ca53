// image/fatal_signal_cleanup.h: a process ended by a second signal during a long pass
// leaves none of its outputs' temporaries behind; a registration that ended (the file
// renamed into place or removed by its owner) no longer names the path.
#include "image/fatal_signal_cleanup.h"

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
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

// The viewer or `render --frames` holding finished frames in a CommitGroup during a pass
// of several seconds: the first Ctrl-C asks for a clean stop, a second one after the grace
// time ends the process at once. Its temporaries must go with it.
TEST_F(FatalSignalCleanup, ASecondSignalLeavesNoTemporaryBehind) {
    GTEST_FLAG_SET(death_test_style, "fast");  // the child keeps this test's scratch directory
    const fs::path out = dir_ / "frame.0001.exr";
    EXPECT_EXIT(
        {
            const InterruptScope interrupts;
            CommitGroup outputs;
            std::ofstream(outputs.add(out)) << "finished frame";
            ::raise(SIGINT);  // recorded: the pass goes on
            std::this_thread::sleep_for(std::chrono::duration<double>(kInterruptGraceSeconds + 0.2));
            ::raise(SIGINT);  // ends the process here
            std::_Exit(0);
        },
        ::testing::KilledBySignal(SIGINT), "no checkpoint written");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), {}), 0);
}

}  // namespace
}  // namespace tessera
