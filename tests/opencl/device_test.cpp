// The default OpenCL device order (host/opencl/device.cpp, rank_cl_devices): discrete GPU
// over integrated GPU over accelerator over CPU, more compute units first within a class,
// list order on ties.
#include <gtest/gtest.h>

#include "opencl/device.h"

namespace tessera {
namespace {

ClDeviceInfo dev(const char* type, bool unified, unsigned units) {
    ClDeviceInfo d;
    d.type = type;
    d.unified_memory = unified;
    d.compute_units = units;
    return d;
}

TEST(DeviceRank, DiscreteGpuBeatsIntegratedGpuListedFirst) {
    // ICD order with the integrated GPU's platform first, as on many laptops.
    const std::vector<ClDeviceInfo> devs = {dev("CPU", true, 16), dev("GPU", true, 96), dev("GPU", false, 40),
                                            dev("accelerator", false, 8)};
    EXPECT_EQ(rank_cl_devices(devs), (std::vector<size_t>{2, 1, 3, 0}));
}

TEST(DeviceRank, MoreComputeUnitsFirstThenListOrder) {
    const std::vector<ClDeviceInfo> devs = {dev("GPU", false, 28), dev("GPU", false, 80), dev("GPU", false, 28),
                                            dev("other", false, 100)};
    EXPECT_EQ(rank_cl_devices(devs), (std::vector<size_t>{1, 0, 2, 3}));
}

TEST(DeviceRank, EmptyListGivesEmptyOrder) { EXPECT_TRUE(rank_cl_devices({}).empty()); }

}  // namespace
}  // namespace tessera
