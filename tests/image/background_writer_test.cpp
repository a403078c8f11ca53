// BackgroundWriter: one write at a time, in order, off the caller's thread, and a write's
// error surfaces at the next start() or wait().
#include "image/background_writer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <future>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "image/atomic_file.h"
#include "support/scratch_dir.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

TEST(BackgroundWriter, StartReturnsWhileTheWriteRuns) {
    std::promise<void> release;
    std::shared_future<void> released = release.get_future().share();
    std::atomic<bool> finished{false};
    std::thread::id writer_thread;
    BackgroundWriter writes;
    // A start() that ran the write itself would wait here 10 s and then find `finished`.
    writes.start([&] {
        writer_thread = std::this_thread::get_id();
        released.wait_for(10s);
        finished = true;
    });
    EXPECT_FALSE(finished);
    release.set_value();
    writes.wait();
    EXPECT_TRUE(finished);
    EXPECT_NE(writer_thread, std::this_thread::get_id());
}

TEST(BackgroundWriter, WritesRunOneAtATimeInTheOrderStarted) {
    std::vector<int> order;  // touched by one write at a time, or the count below says otherwise
    std::atomic<int> running{0}, most{0};
    BackgroundWriter writes;
    for (int i = 0; i < 6; ++i)
        writes.start([&, i] {
            const int now = ++running;
            most = std::max(most.load(), now);
            std::this_thread::sleep_for(5ms);  // long enough for a second thread to overlap
            order.push_back(i);
            --running;
        });
    writes.wait();
    EXPECT_EQ(most, 1);
    EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3, 4, 5}));
}

TEST(BackgroundWriter, AWritesErrorIsRethrownByTheNextStartWhichRunsNothing) {
    BackgroundWriter writes;
    writes.start([] { throw std::runtime_error("cannot write 'frame.0003.exr': No space left on device"); });
    bool ran = false;
    try {
        writes.start([&] { ran = true; });
        FAIL() << "start() returned over the write before's error";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()), "cannot write 'frame.0003.exr': No space left on device");
    }
    EXPECT_NO_THROW(writes.wait());  // the error is given once
    EXPECT_FALSE(ran);
}

TEST(BackgroundWriter, WaitRethrowsAndTheDestructorWaitsWithoutThrowing) {
    BackgroundWriter writes;
    writes.start([] { throw std::logic_error("first"); });
    EXPECT_THROW(writes.wait(), std::logic_error);
    std::atomic<bool> finished{false};
    {
        BackgroundWriter dropped;
        dropped.start([&] {
            std::this_thread::sleep_for(20ms);
            finished = true;
            throw std::runtime_error("dropped by the destructor");
        });
    }  // must neither throw nor return before the write ends
    EXPECT_TRUE(finished);
}

TEST(BackgroundWriter, CheckRethrowsAnEndedWritesErrorWithoutWaitingForARunningOne) {
    BackgroundWriter writes;
    std::promise<void> release;
    std::shared_future<void> released = release.get_future().share();
    writes.start([released] { released.wait_for(10s); });
    EXPECT_NO_THROW(writes.check());  // still running: check() returns at once
    release.set_value();
    writes.wait();
    writes.start([] { throw std::runtime_error("disk full"); });
    for (int i = 0; i < 1000; ++i) {  // up to 10 s for the worker to end
        try {
            writes.check();
        } catch (const std::runtime_error& e) {
            EXPECT_EQ(std::string(e.what()), "disk full");
            EXPECT_NO_THROW(writes.wait());
            return;
        }
        std::this_thread::sleep_for(10ms);
    }
    FAIL() << "check() never gave the ended write's error";
}

// As a --frames run uses it: frame 0's file is written, frame 1's write fails, and the
// run unwinds from the next start(): neither the written frame nor any temporary stays.
class BackgroundWriterCommitTest : public test::ScratchDirTest {};

TEST_F(BackgroundWriterCommitTest, AFailedWriteLeavesNoFileOfTheRun) {
    try {
        CommitGroup outputs;
        BackgroundWriter writes;
        writes.start([&] { outputs.write(dir_ / "f.0000.exr", [](const fs::path& t) { write_file_atomic(t, "0", 1); }); });
        writes.start([&] {
            outputs.write(dir_ / "f.0001.exr", [](const fs::path&) { throw std::runtime_error("No space left"); });
        });
        writes.start([] {});
        outputs.commit();
        FAIL() << "the failed write went unseen";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()), "No space left");
    }
    EXPECT_TRUE(fs::is_empty(dir_)) << "a file of the failed run stayed";
}

}  // namespace
}  // namespace tessera
