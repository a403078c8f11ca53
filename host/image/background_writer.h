// Output written while the next work goes on: a --frames run writes frame N's EXR and
// PNG on a worker thread while it renders frame N+1. Writing a 512² frame's two files
// takes ~150 ms on the 2-core guest (~290 ms before their encoders were sped up), a
// quarter of a Sibenik tic frame on the CPU and ten igi frames on a GPU
// (bench/results/frame_output.md).
#pragma once
#include <functional>
#include <future>

namespace tessera {

/// Runs one write at a time on a worker thread. The writes run in the order started, each
/// alone: start() first waits for the write before. An exception a write throws is
/// rethrown, unchanged, by the next start() or wait() (and that write is not started).
/// The destructor waits for a write in flight and drops its exception (the owner is
/// unwinding from an error of its own, or called wait() already): declare the writer
/// after whatever its writes use (a CommitGroup, say), so that it ends first.
class BackgroundWriter {
public:
    BackgroundWriter() = default;
    ~BackgroundWriter();
    BackgroundWriter(const BackgroundWriter&) = delete;
    BackgroundWriter& operator=(const BackgroundWriter&) = delete;

    /// Waits for the write in flight (rethrowing its exception), then runs `write` on a
    /// new worker thread and returns at once; where no thread can be started, runs it
    /// here. `write` must own or outlive what it reads.
    void start(std::function<void()> write);
    /// Waits for the write in flight, if any, and rethrows its exception.
    void wait();
    /// Without waiting: where the write in flight has ended, rethrows its exception (and
    /// forgets it), so a caller polling between passes stops at a failed write at once.
    void check();

private:
    std::future<void> in_flight_;
};

}  // namespace tessera
