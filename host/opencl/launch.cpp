#include "opencl/launch.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace tessera {

TileSizer::TileSizer(double budget_seconds, size_t fixed_groups, size_t first_groups)
    : budget_(budget_seconds), fixed_(fixed_groups), first_(std::max<size_t>(1, first_groups)) {}

size_t TileSizer::next(size_t remaining) const {
    if (fixed_ > 0) return std::min(fixed_, remaining);
    if (budget_ <= 0.0) return remaining;
    if (rate_ <= 0.0) return std::min(first_, remaining);
    const double fit = std::floor(rate_ * budget_);
    const double cap = 4.0 * static_cast<double>(std::max<size_t>(last_, 1));
    const double n = std::clamp(std::min(fit, cap), 1.0, static_cast<double>(remaining));
    return static_cast<size_t>(n);
}

void TileSizer::record(size_t groups, double seconds) {
    if (groups == 0) return;
    last_ = groups;
    // A tile too quick to time (clock resolution) counts as fast as the cap allows.
    rate_ = seconds > 0.0 ? static_cast<double>(groups) / seconds : 1e30;
}

std::string cl_error_name(int error) {
    switch (error) {
        case CL_OUT_OF_RESOURCES: return "CL_OUT_OF_RESOURCES";
        case CL_OUT_OF_HOST_MEMORY: return "CL_OUT_OF_HOST_MEMORY";
        case CL_MEM_OBJECT_ALLOCATION_FAILURE: return "CL_MEM_OBJECT_ALLOCATION_FAILURE";
        case CL_INVALID_COMMAND_QUEUE: return "CL_INVALID_COMMAND_QUEUE";
        case CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST: return "CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST";
        default: return "error";
    }
}

bool is_resource_error(int error) {
    return error == CL_OUT_OF_RESOURCES || error == CL_MEM_OBJECT_ALLOCATION_FAILURE ||
           error == CL_OUT_OF_HOST_MEMORY || error == CL_INVALID_COMMAND_QUEUE;
}

namespace {
std::string mib(unsigned long long bytes) {
    char b[32];
    std::snprintf(b, sizeof b, "%.1f MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
    return b;
}
}  // namespace

std::string launch_failure_message(const LaunchFailure& f) {
    std::string s = "OpenCL kernel " + f.kernel + " on " + f.device + " failed: " + cl_error_name(f.error) + " (" +
                    std::to_string(f.error) + ") from " + f.call + ", in a launch of " +
                    std::to_string(f.tile_items) + " of " + std::to_string(f.launch_items) + " work-items. ";
    s += "Likely causes: (1) the display driver's watchdog stopped a long launch: ";
    if (f.budget_ms > 0.0) {
        char b[64];
        std::snprintf(b, sizeof b, "%g", f.budget_ms);
        s += std::string("launches are tiled to about ") + b + " ms; set TESSERA_CL_LAUNCH_MS lower";
    } else {
        s += "launches on this device are not tiled; set TESSERA_CL_LAUNCH_MS (e.g. 100)";
    }
    s += ", or use a GPU that drives no display; (2) private memory: ";
    if (f.private_bytes > 0)
        s += "the kernel uses " + std::to_string(f.private_bytes) + " bytes per work-item (CL_KERNEL_PRIVATE_MEM_SIZE), " +
             std::to_string(f.private_bytes * f.work_group) + " per work-group of " + std::to_string(f.work_group);
    else
        s += "the device does not report the kernel's use (CL_KERNEL_PRIVATE_MEM_SIZE)";
    s += "; (3) device memory: Tessera's buffers take " + mib(f.buffer_bytes) + " of the device's " +
         mib(f.global_mem) + ". Try a smaller --width/--height, another --device, or --backend embree";
    return s;
}

std::string failed_launch(const InFlightLaunches& in_flight) {
    for (const auto& [name, event] : in_flight) {
        cl_int status = CL_COMPLETE;
        if (event.getInfo(CL_EVENT_COMMAND_EXECUTION_STATUS, &status) != CL_SUCCESS || status < 0) return name;
    }
    return "";
}

double event_seconds(const cl::Event& e) {
    cl_ulong start = 0, end = 0;
    if (e.getProfilingInfo(CL_PROFILING_COMMAND_START, &start) != CL_SUCCESS ||
        e.getProfilingInfo(CL_PROFILING_COMMAND_END, &end) != CL_SUCCESS)
        return -1.0;
    return end > start ? static_cast<double>(end - start) * 1e-9 : 0.0;
}

void record_finished_tiles(TileSizer& sizer, PendingTiles& pending) {
    size_t done = 0;
    for (; done < pending.tiles.size(); ++done) {
        const auto& [groups, event] = pending.tiles[done];
        const cl_int status = event.getInfo<CL_EVENT_COMMAND_EXECUTION_STATUS>();
        if (status > CL_COMPLETE) break;  // queued, submitted or running: later tiles too (in-order queue)
        const double seconds = status == CL_COMPLETE ? event_seconds(event) : -1.0;
        if (seconds >= 0.0) sizer.record(groups, seconds);
    }
    pending.tiles.erase(pending.tiles.begin(), pending.tiles.begin() + static_cast<std::ptrdiff_t>(done));
}

void enqueue_tiled(cl::CommandQueue& queue, cl::Kernel& k, size_t work_items, size_t work_group, TileSizer& sizer,
                   PendingTiles& pending, std::vector<cl::Event>& events, size_t& tile_items, int fail_after_first) {
    if (sizer.timed()) record_finished_tiles(sizer, pending);
    const size_t groups = (work_items + work_group - 1) / work_group;
    size_t done = 0;
    while (done < groups) {
        const size_t n = sizer.next(groups - done);
        tile_items = n * work_group;
        cl::Event event;
        const auto t0 = std::chrono::steady_clock::now();
        queue.enqueueNDRangeKernel(k, cl::NDRange(done * work_group), cl::NDRange(n * work_group),
                                   cl::NDRange(work_group), nullptr, &event);
        if (fail_after_first != 0) throw cl::Error(fail_after_first, "clFinish");
        events.push_back(event);
        done += n;
        if (!sizer.timed()) continue;
        if (!sizer.has_rate() && done < groups) {
            // The one wait: this tile's time sizes the rest of the launch.
            event.wait();
            const double seconds = event_seconds(event);
            sizer.record(n, seconds >= 0.0 ? seconds
                                           : std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        } else {
            pending.tiles.emplace_back(n, event);
        }
    }
}

}  // namespace tessera
