// Kernel launches in tiles, and what to say when a launch fails for resources.
//
// One dispatch of a whole frame can run for seconds; a GPU that drives a display is
// stopped by its driver's watchdog long before that matters to us (Windows TDR: 2 s by
// default; the Linux and macOS display drivers: a few seconds) and the launch fails with
// a bare CL_OUT_OF_RESOURCES or CL_INVALID_COMMAND_QUEUE. So a launch over N work-items
// is split into tiles of whole work-groups by global work offset (clEnqueueNDRangeKernel's
// global_work_offset; every kernel indexes its work with get_global_id(0), which includes
// the offset), each tile sized from the device times of earlier tiles so that it takes
// about a set budget. The times are the tiles' own profiling timestamps, read once they
// have finished, so tiling adds no host wait between launches (but one, to time a
// kernel's first tile). Work-item i's output depends only on i, so results are the same
// bit for bit whatever the tiling (tests/opencl/launch_test.cpp).
#pragma once
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "opencl/cl.h"

namespace tessera {

/// The default launch budget on GPU and accelerator devices, milliseconds: 20× under
/// the shortest common watchdog (Windows TDR, 2 s), so a tile sized from an earlier,
/// faster one stays far from it, while the launch overhead of a tile (tens of
/// microseconds) stays below 0.1% of it. CPU devices have no watchdog and run each launch
/// whole.
constexpr double kDefaultGpuLaunchMs = 100.0;

/// Tile sizes, in work-groups, for the launches of one kernel. The rate (work-groups per
/// second) measured on one tile sizes the next; it carries over to the kernel's next
/// launch. Growth is capped at 4× per tile because the first, small tiles are dominated
/// by launch overhead and a noisy short time would overshoot the budget.
class TileSizer {
public:
    /// budget_seconds <= 0: each launch is one tile. fixed_groups > 0: every tile has
    /// exactly that many work-groups, budget ignored (tests). first_groups: the first
    /// tile's size before any time is known (at least 1).
    TileSizer(double budget_seconds, size_t fixed_groups, size_t first_groups);

    /// Work-groups in the next tile when `remaining` (> 0) are left: between 1 and remaining.
    size_t next(size_t remaining) const;

    /// Records that a tile of `groups` work-groups took `seconds` (its device time).
    void record(size_t groups, double seconds);

    /// Whether tiles are timed (their times sized the tiles that follow).
    bool timed() const { return fixed_ == 0 && budget_ > 0.0; }
    /// Whether a tile's time has been recorded.
    bool has_rate() const { return rate_ > 0.0; }

private:
    double budget_;
    size_t fixed_;
    size_t first_;
    size_t last_ = 0;    // size of the last recorded tile
    double rate_ = 0.0;  // work-groups per second from the last tile; 0: none yet
};

/// What the message about a failed launch names.
struct LaunchFailure {
    std::string device;
    std::string kernel;
    int error = 0;                  ///< OpenCL error code
    std::string call;               ///< the failing call, e.g. "clFinish"
    size_t tile_items = 0;          ///< work-items in the tile that failed
    size_t launch_items = 0;        ///< work-items of the whole launch
    double budget_ms = 0.0;         ///< launch budget (0: launches are not tiled)
    size_t private_bytes = 0;       ///< CL_KERNEL_PRIVATE_MEM_SIZE per work-item (0: unknown)
    size_t work_group = 0;          ///< work-items per work-group
    unsigned long long buffer_bytes = 0;  ///< device buffers Tessera holds
    unsigned long long global_mem = 0;    ///< CL_DEVICE_GLOBAL_MEM_SIZE
};

/// "CL_OUT_OF_RESOURCES" etc. for the codes a launch can fail with, else "error".
std::string cl_error_name(int error);

/// Whether `error` from an enqueue, a read or a finish means the device ran out of
/// something or stopped the kernel: CL_OUT_OF_RESOURCES, CL_MEM_OBJECT_ALLOCATION_FAILURE,
/// CL_OUT_OF_HOST_MEMORY, CL_INVALID_COMMAND_QUEUE (a queue the driver reset).
bool is_resource_error(int error);

/// One message naming the device, kernel, error and call, the tile and launch sizes, and
/// the likely causes with their numbers: a display watchdog (with the budget and how to
/// lower it), private memory per work-item and per work-group, device memory in use.
std::string launch_failure_message(const LaunchFailure& f);

/// A kernel's tiles enqueued and not yet timed: their work-group counts and events.
struct PendingTiles {
    std::vector<std::pair<size_t, cl::Event>> tiles;
};

/// Launches queued since the queue was last waited for, oldest first: each tile's kernel
/// name and event.
using InFlightLaunches = std::vector<std::pair<std::string, cl::Event>>;

/// The kernel of the first launch of `in_flight` whose event reports a failure (a negative
/// CL_EVENT_COMMAND_EXECUTION_STATUS, or none to be had), or "" when none has failed: a
/// launch queued without a wait fails where the queue is next waited for, and the message
/// must name it, not the launch that waited.
std::string failed_launch(const InFlightLaunches& in_flight);

/// Seconds event `e` (a finished command on a queue made with CL_QUEUE_PROFILING_ENABLE)
/// ran on the device: CL_PROFILING_COMMAND_END − CL_PROFILING_COMMAND_START; −1 when the
/// device gives no timestamps (a tile waited for is then timed by the host's clock).
double event_seconds(const cl::Event& e);

/// Records in `sizer` the device time of every tile of `pending` that has finished, in
/// enqueue order, and drops them (a failed one is dropped unrecorded: its failure is
/// reported where the queue is next waited for).
void record_finished_tiles(TileSizer& sizer, PendingTiles& pending);

/// Enqueues `k` over `work_items` work-items (rounded up to whole work-groups of
/// `work_group` items) in tiles from `sizer`, without waiting: a timed sizer learns each
/// tile's device time from its event once it has finished (`pending`, recorded by
/// record_finished_tiles at the kernel's next launch). The one wait is for the first tile
/// of a kernel whose rate is not known yet while more tiles follow, which it sizes. The
/// tiles' events are appended to `events`. `tile_items` is set to the size of the tile
/// being enqueued (for a failure message). `fail_after_first` (a test hook,
/// TESSERA_CL_FAIL_LAUNCH; 0: off) throws cl::Error with that code from "clFinish" after
/// the first tile. Throws cl::Error.
void enqueue_tiled(cl::CommandQueue& queue, cl::Kernel& k, size_t work_items, size_t work_group, TileSizer& sizer,
                   PendingTiles& pending, std::vector<cl::Event>& events, size_t& tile_items,
                   int fail_after_first = 0);

}  // namespace tessera
