// Checkpoints: the accumulation state of a render saved to disk, so that an interrupted
// render can be resumed and finish with exactly the image an uninterrupted one gives.
//
// That works because pass i always draws the same samples (the RNG is counter-based on
// seed, pixel and pass, kernels/shared/rng.h): restoring the Accumulator bit for bit and
// adding passes N, N+1, ... in order gives the same double sums as never stopping.
//
// File format, version 4. All integers and doubles are little-endian (the host's own
// byte order; big-endian hosts are rejected at compile time). Strings are a u32 byte
// count followed by the bytes (no terminator).
//
//   char[8]  magic "TSCKPT01"
//   u32      format version (4; 3 has the same layout, but an igi-family run (igi,
//            ais, ais-max, ic, tic) refuses 2 and 3, whose passes differ; 2, still read
//            for pt and direct, lacks K and the method's sums; 1 also lacked the
//            method's settings and is refused)
//   u32      floats per pixel and pass (TS_PASS_FLOATS, 10)
//   i32      width, i32 height
//   u32      passes done (N: passes 0..N-1 are in the sums)
//   u32      spp target of the run that wrote it (informational)
//   u64      settings hash: FNV-1a 64 over the identity record's bytes as stored below
//   identity record (RunIdentity), in this order:
//     string scene file path (absolute, normalised; "" for a scene built in code)
//     u64    FNV-1a 64 of the scene file's bytes (0 if no file)
//     u64    FNV-1a 64 of the loaded scene data (triangles, materials, textures, camera)
//     string method, u32 seed, u32 shadow samples, u32 max depth, u32 max scatter,
//     i32 width, i32 height,
//     string backend ("opencl" or "embree")
//     string the method's other settings ("--tile 3 --vpl-paths 64 ...": RunIdentity)
//   u32      K, the method's own sum arrays (MethodSums; 0 for most runs, at most 64)
//   u64[K]   their lengths in doubles, each 0, width·height or 3·width·height
//   f64[width·height·TS_PASS_FLOATS]  sums per pixel (Accumulator::sums)
//   f64[width·height·3]               sums of squared radiance
//   u32[width·height]                 hit counts
//   f64[length k] for each of the K    the method's sums, in its order
//   u64      checksum: FNV-1a 64 over every byte before it
//
// The identity is stored field by field as well as hashed, so that a mismatch can name
// the setting that differs ("... was made with --seed 1, this run has --seed 2").
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "render/accumulator.h"
#include "render/run_identity.h"
#include "util/hash.h"

namespace tessera {

/// The sums a method keeps beside the accumulator for its own AOV channels
/// (Integrator::aov_sums: the igi family's components and AIS's guidance with --aov), in
/// the method's order. A checkpoint holds them so a resumed render's channels cover every
/// pass, as the uninterrupted render's do.
using MethodSums = std::vector<std::vector<double>>;


/// The checkpoint path for an output image: `out` with its extension replaced by .ckpt.
std::filesystem::path checkpoint_path_for(const std::filesystem::path& out);

/// Writes `acc` and the method's sums (pointers, none null) with `id` to `path`
/// atomically (image/atomic_file.h): a failed or interrupted write leaves any previous
/// checkpoint intact. Throws RuntimeError.
void save_checkpoint(const std::filesystem::path& path, const RunIdentity& id, uint32_t spp_target,
                     const Accumulator& acc, const std::vector<const std::vector<double>*>& method_sums = {});

/// Checks `path` as a file, before a run's set-up: the magic, version, sizes and checksum
/// (not which run made it, nor the values, which load_checkpoint checks). Reads the file
/// once, holding 1 MiB of it at a time. Throws InputError as load_checkpoint does.
void check_checkpoint_file(const std::filesystem::path& path);

/// Reads `path` into `acc` (which must be sized id.width × id.height) after checking the
/// magic, version, sizes, checksum and that it was made by a run with identity `id`.
/// The method's sums go to `method_sums` when given (replacing its contents), else are
/// checked and dropped; the file's format version to `format_version` when given (2 has
/// no method sums). Returns the number of passes restored. Throws InputError naming
/// `path` and what is wrong (missing, truncated, corrupt, or which setting differs).
uint32_t load_checkpoint(const std::filesystem::path& path, const RunIdentity& id, Accumulator& acc,
                         MethodSums* method_sums = nullptr, uint32_t* format_version = nullptr);

}  // namespace tessera
