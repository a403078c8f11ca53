#include "device/kernel_table.h"

#include <type_traits>

namespace tessera {

const KernelInfo& kernel_info(KernelId k) {
#define TS_KERNEL_INFO(id, name, program, floats, words, fn, cl_packets, packets) \
    KernelInfo{name, program, floats, words, cl_packets},
    static const KernelInfo table[kKernelCount] = {TS_KERNEL_TABLE(TS_KERNEL_INFO)};
#undef TS_KERNEL_INFO
    return table[static_cast<int>(k)];
}

const KernelInputInfo& input_info(KernelInput in) {
    static const KernelInputInfo table[kKernelInputCount] = {
#define TS_INPUT_INFO(name, field, type, what) {what, std::is_same_v<TS_ELEMENT_TYPE(type), uint32_t>},
        TS_KERNEL_INPUTS(TS_INPUT_INFO)
#undef TS_INPUT_INFO
    };
    return table[static_cast<int>(in)];
}

}  // namespace tessera
