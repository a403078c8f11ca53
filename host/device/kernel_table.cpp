#include "device/kernel_table.h"

namespace tessera {

const KernelInfo& kernel_info(KernelId k) {
#define TS_KERNEL_INFO(id, name, program, floats, words, fn) KernelInfo{name, program, floats, words},
    static const KernelInfo table[kKernelCount] = {TS_KERNEL_TABLE(TS_KERNEL_INFO)};
#undef TS_KERNEL_INFO
    return table[static_cast<int>(k)];
}

const KernelInputInfo& input_info(KernelInput in) {
    static const KernelInputInfo table[kKernelInputCount] = {
        {"VPL", false}, {"VPL set table", true}, {"ic G-buffer", false},
        {"ic octree", false}, {"ic record lists", true}, {"ic records", false},
        {"ic record surfaces", false}, {"ic visibility", true},
        {"igi surface", false}, {"igi media", false},
    };
    return table[static_cast<int>(in)];
}

}  // namespace tessera
