// The frame loop's messages in a distributed render (docs/distributed.md): workers
// (ranks > 0) render their passes and send them to rank 0, which adds every pass to the
// one accumulator in pass order, exactly as a one-process render does, so the image is
// bit-identical for any number of ranks.
#pragma once
#include <cstdint>
#include <vector>

#include "integrators/integrator.h"
#include "render/cluster.h"

namespace tessera {

/// Rank 0's side: receives passes from workers and stops them at the end (or on failure).
class PassCollector {
public:
    /// `pass_floats`: width × height × TS_PASS_FLOATS, the size of every pass.
    PassCollector(Cluster& cluster, size_t pass_floats);
    /// Stops the workers (exit code 1) if stop() was not called: an exception is leaving.
    ~PassCollector();
    PassCollector(const PassCollector&) = delete;
    PassCollector& operator=(const PassCollector&) = delete;

    /// Receives pass `pass` from its owner `rank` into `out` and returns true; returns
    /// false if that worker was interrupted (SIGINT/SIGTERM) instead. Throws RankFailure
    /// "rank R of N: <cause>" if the worker failed, RuntimeError if it broke the protocol.
    bool receive(int rank, uint32_t pass, std::vector<float>& out);

    /// Sends every worker Stop with `exit_code` (0: the render is complete) and receives
    /// until each one's last message. Runs once; later calls do nothing. Never throws.
    void stop(int exit_code) noexcept;

private:
    Cluster& cluster_;
    size_t pass_floats_;
    std::vector<char> buffer_;
    std::vector<bool> finished_;  ///< per rank: its terminal message has arrived
    bool stopped_ = false;
};

/// A worker's side: renders passes first + rank, first + rank + size, ... below `spp`
/// (frame.pass set to each), sends each to rank 0, then its terminal message, and waits
/// for Stop. Returns if Stop says the render is complete; otherwise throws a silent
/// RankFailure with Stop's exit code (rank 0 reports the cause).
void run_worker(Cluster& cluster, Integrator& integrator, TsFrame frame, uint32_t first, uint32_t spp);

}  // namespace tessera
