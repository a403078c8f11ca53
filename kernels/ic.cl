/* Instant caching on OpenCL devices (shared/ic.h): the interpolation kernel (octree lookup over the
 * records, set as named inputs), and the record-VPL pair and gather kernels. Built with
 * doubles where the device has cl_khr_fp64 (shared/compat.h TS_HAS_DOUBLE). */
#include "shared/layout.h"
#include "tracer.h"
#include "shared/ic.h"

TS_PIXEL_KERNEL(ic_interpolate, ts_ic_interpolate_kernel_pixel, TS_IC_INTERP_FLOATS)

/* The record–VPL work of the cache (placement, the temporal update): item i is one pair's
 * shadow ray, or one record's gather sum over its visibility row. */
TS_ITEM_KERNEL(ic_pair_pass, ts_ic_pair_item, TS_IC_PAIR_FLOATS)

TS_ITEM_KERNEL(ic_gather_pass, ts_ic_gather_item, TS_IC_GATHER_FLOATS)
