// The processes of one render: this process alone, or the ranks of an MPI job started
// by `mpirun -n N tessera render ...` (docs/distributed.md). The frame loop
// (render/renderer.cpp) and the render command use it; only render/cluster_mpi.cpp
// calls MPI, and it is compiled only when CMake finds MPI (TESSERA_MPI).
//
// Messages between ranks go only between rank 0 and one other rank ("a worker"), on
// MPI_COMM_WORLD, in the order of docs/distributed.md: a worker sends Pass messages in
// increasing pass order, then exactly one terminal message (Done, Error or Interrupt);
// rank 0 sends each worker exactly one Stop (an int exit code: 0 when the render is
// complete) and receives until that worker's terminal message.
#pragma once
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace tessera {

/// The MPI tags of the frame loop's messages (values are part of no file format).
enum class RankMessage : int {
    Pass = 1,       ///< uint32 pass index, then width × height × TS_PASS_FLOATS floats
    Done = 2,       ///< the worker rendered all its passes or saw Stop (no payload)
    Error = 3,      ///< int exit code (1 runtime, 2 bad input), then the message text
    Interrupt = 4,  ///< the worker got SIGINT/SIGTERM (no payload)
    Stop = 5,       ///< rank 0 to a worker: int exit code (0: complete)
};

/// A failure of a distributed render. On rank 0 what() is the one message for the whole
/// job ("rank 1 of 2: <cause>"); on the other ranks it is silent (empty what()): rank 0
/// reports. main() exits with `exit_code` (1 runtime, 2 bad input, 130 interrupted).
struct RankFailure : std::runtime_error {
    RankFailure(const std::string& message, int code) : std::runtime_error(message), exit_code(code) {}
    int exit_code;
    bool silent() const { return what()[0] == '\0'; }
};

/// The exit code main() gives `e` (the contract of host/main.cpp): 2 for InputError, 130
/// for Interrupted, RankFailure's own, 1 otherwise.
int exit_code_of(const std::exception_ptr& e);

class Cluster {
public:
    virtual ~Cluster() = default;
    virtual int rank() const = 0;
    virtual int size() const = 0;

    /// Collective (every rank calls it): runs `step` here, then, when size() > 1, learns
    /// whether it failed on any rank. If it did, throws RankFailure on every rank: on rank
    /// 0 naming the lowest failing rank, its cause and how many ranks failed; elsewhere
    /// silent. Alone (size() == 1) an exception of `step` propagates unchanged.
    void step(const std::function<void()>& step);

    /// Whether step() has been called in this process (its ranks have begun the render's
    /// collective steps, so a failure now must not start another: host/main.cpp).
    bool stepped() const { return stepped_; }

    /// Collective: rank 0's `value` on every rank.
    virtual uint32_t broadcast(uint32_t value) = 0;

    /// Blocking send of one message to rank `to`.
    virtual void send(int to, RankMessage tag, const void* data, size_t bytes) = 0;
    /// Blocking receive of the next message from rank `from` (any tag) into `data`
    /// (resized to the payload); returns its tag.
    virtual RankMessage receive(int from, std::vector<char>& data) = 0;
    /// Whether a message with `tag` from `from` is waiting (does not receive it).
    virtual bool waiting(int from, RankMessage tag) = 0;

protected:
    /// The collective part of step(): `failure` is this rank's (null: success). Returns
    /// normally only if no rank failed.
    virtual void agree(const std::exception_ptr& failure) = 0;

private:
    bool stepped_ = false;
};

/// This process's cluster: the MPI world when this binary was built with MPI and started
/// by an MPI launcher (OMPI_COMM_WORLD_SIZE, PMI_SIZE or PMIX_RANK in the environment;
/// MPI_Init runs on the first call), else this process alone. MPI_Finalize runs at exit.
Cluster& world_cluster();

/// Whether this process was started by an MPI launcher and this binary was built with MPI
/// (then world_cluster() is the MPI world).
bool launched_by_mpi();

/// Whether this binary was built with MPI (TESSERA_MPI found it).
bool built_with_mpi();

/// The owner of pass `pass` when a render on `ranks` ranks starts at pass `first`
/// (passes before it come from a checkpoint): round robin, (pass − first) mod ranks.
/// Which rank renders a pass never changes the image (docs/distributed.md).
inline int pass_owner(uint32_t pass, uint32_t first, int ranks) { return int((pass - first) % uint32_t(ranks)); }

}  // namespace tessera
