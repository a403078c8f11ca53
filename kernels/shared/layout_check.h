/* How the buffer layouts shared by the host (C++) and the kernels (OpenCL C) are
 * declared: each record is a set of named offsets (TS_<RECORD>_<FIELD>, in floats from the
 * record's start) and its size TS_<RECORD>_FLOATS. Every buffer is an array of 32-bit
 * `float` or `uint`; no float3 (its size differs between OpenCL and C++), no pointers.
 * Index a buffer only through these names. The layouts live by concern:
 *   shared/layout_scene.h  the scene: BVH, triangles, materials, medium, textures, lights
 *   shared/layout_rays.h   ray batches and hits (TS_NO_HIT)
 *   shared/frame.h         TsFrame, the per-frame parameters, and the work-group size
 *   shared/layout_igi.h    VPLs and the igi / AIS kernels' outputs and item lists
 *   shared/layout_ic.h     instant caching's G-buffer, records, octree and item lists
 *   shared/layout_pass.h   one pass's per-pixel output
 * Each ends with C++ checks, built on this header, that its records' fields tile them
 * exactly (no gap, no overlap, the last field ending at the record size), so a field added
 * or resized without the check's list (or the other way round) does not build. C++ only:
 * the OpenCL compiler never includes this. */
#ifndef TS_LAYOUT_CHECK_H
#define TS_LAYOUT_CHECK_H
#ifdef __cplusplus
#include <cstddef>
#include <initializer_list>
#include <type_traits>

namespace tessera::layout_check {
struct Field {
    int offset, width;
};
constexpr bool tiles(std::initializer_list<Field> fields, int total) {
    int next = 0;
    for (const Field& f : fields) {
        if (f.offset != next || f.width <= 0) return false;
        next += f.width;
    }
    return next == total;
}
}  // namespace tessera::layout_check
#endif /* __cplusplus */
#endif /* TS_LAYOUT_CHECK_H */
