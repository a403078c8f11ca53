// `tessera devices`: lists OpenCL platforms and devices.
#include <cstdio>
#include <vector>

#include "cli/commands.h"
#include "opencl/device.h"

namespace tessera::cli {

void add_devices_command(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("devices", "List OpenCL platforms and devices");
    cmd->callback([] {
        auto devs = list_cl_devices();
        if (devs.empty()) {
            std::printf("no OpenCL platform found (install an ICD, e.g. pocl-opencl-icd%s); "
                        "--backend embree needs none\n", no_device_hint().c_str());
            return;
        }
        // Listed in the default order (rank_cl_devices), the default marked; [i] is the
        // index --device takes.
        const std::vector<size_t> order = rank_cl_devices(devs);
        for (size_t r = 0; r < order.size(); ++r) {
            const ClDeviceInfo& d = devs[order[r]];
            const char* kind = d.type == "GPU" ? (d.unified_memory ? "GPU (integrated)" : "GPU (discrete)") : d.type.c_str();
            std::printf("[%d] %s: %s%s\n    %s, %s, driver %s, %u compute units, %.1f GiB, max alloc %.1f GiB, "
                        "%s traversal\n",
                        d.index, d.platform_name.c_str(), d.name.c_str(), r == 0 ? "  (default)" : "", kind,
                        d.version.c_str(), d.driver.c_str(), d.compute_units, d.global_mem / 1073741824.0,
                        d.max_alloc / 1073741824.0, cl_device_prefers_packets(d)       ? "16-ray packet"
                        : cl_device_prefers_short_stack(d) ? "per-ray short-stack"
                                                           : "per-ray");
        }
    });
}

}  // namespace tessera::cli
