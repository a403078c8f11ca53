// The OBJ checks tinyobjloader does not make: a line scan that rejects, with the file and
// line, what the parser would silently change or drop (see scenes/README.md, "Meshes and
// materials"), and that collects the mtllib and usemtl statements for the MTL checks.
#pragma once
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace tessera::scene_detail {

/// An mtllib statement: the MTL path (beside the OBJ) and its line.
struct MtlLibLine {
    size_t line = 0;
    std::string name;              ///< as written
    std::filesystem::path file;    ///< the OBJ's folder / name
};

/// A usemtl statement: the material name as tinyobjloader reads it (the first token).
struct UseMtlLine {
    size_t line = 0;
    std::string name;
};

struct ObjScan {
    std::vector<MtlLibLine> mtllibs;  ///< in file order, each file once
    std::vector<UseMtlLine> usemtls;  ///< in file order
    size_t triangles = 0;             ///< sum over faces of (vertex count − 2)
    size_t first_polygon_line = 0;    ///< first face of more than 4 vertices (0: none)
};

/// Scans the text of `obj` and throws InputError "<obj>:<line>: ..." naming the value for:
/// - `v` without 3 coordinates, or a coordinate that is not a number in tinyobjloader's
///   grammar or is not finite as a float; `vt` without 1–3 numbers (u, v finite);
///   `vn` without exactly 3 finite numbers;
/// - an `f`, `l` or `p` corner that is not `v`, `v/vt`, `v//vn` or `v/vt/vn` with integer
///   indices; index 0; an index out of range (above the file's count, or relative and
///   reaching before the first element defined so far), including one that overflows;
/// - a face with fewer than 3 corners, an `l` with fewer than 2;
/// - an mtllib naming several files (tinyobjloader reads only the first it finds), an
///   absolute path or one with a folder part (MTL files must be beside the OBJ);
/// - a NUL byte.
ObjScan scan_obj(const std::filesystem::path& obj, std::string_view text);

}  // namespace tessera::scene_detail
