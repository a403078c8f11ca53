// The MTL checks tinyobjloader does not make: a line scan of the statements the loader
// reads, rejecting with the file, line, material and value what the parser would
// silently replace (it reads "Kd nan" as 0 and "Kd 0.5" as (0.5, 0, 0)). The valid
// values are listed in scenes/README.md ("Meshes and materials").
#pragma once
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>

namespace tessera::scene_detail {

/// Where a material is defined.
struct MtlDefinition {
    std::filesystem::path file;
    size_t line = 0;         ///< its newmtl
    size_t map_kd_line = 0;  ///< its map_Kd, 0 for none
};

/// Scans the text of `mtl` and adds each `newmtl` name to `defined`. Throws InputError
/// "<mtl>:<line>: material '<name>': ..." naming the value for:
/// - Kd, Ks, Ke not exactly 3 numbers (tinyobjloader grammar), or one that is negative
///   or not finite as a float (Kd and Ks above 1 are allowed: the loader clamps them);
/// - Ni not one finite number >= 0, or Ni <= 0 in a dielectric (illum 7), since the
///   refraction at its surface divides by it;
/// - illum not one integer in 0..10 (the models the MTL format defines);
/// - a material name defined twice in the MTL files of one OBJ (`defined` holds the
///   earlier ones), since tinyobjloader would give usemtl the first and overrides both;
/// - map_Kd without a file name;
/// - a statement the loader reads (Kd, Ks, Ke, Ni, illum, map_Kd) before any newmtl,
///   which tinyobjloader would drop;
/// - a NUL byte.
/// Other statements (Ka, Ns, d, Tr, Tf, map_* but map_Kd, ...) are not read by the loader
/// and not checked.
void scan_mtl(const std::filesystem::path& mtl, std::string_view text,
              std::map<std::string, MtlDefinition>& defined);

}  // namespace tessera::scene_detail
