// libFuzzer targets for the readers of the viewer's and the tools' inputs, one executable
// per reader (TESSERA_FUZZ_READER, set by tests/fuzz/CMakeLists.txt):
//   1 camera_path_fuzzer   view::read_camera_path   (--camera-path JSON)
//   2 input_script_fuzzer  view::read_input_script  (--input-script JSON)
//   3 checkpoint_fuzzer    load_checkpoint          (--resume)
//   4 exr_fuzzer           read_exr                 (`tessera compare`, --reference)
// The input is written to a file and read back. Expected outcomes: a value that keeps the
// reader's promises (checked below), or tessera::InputError. Any other exception, a crash,
// a leak, undefined behaviour, more than -rss_limit_mb of memory or -timeout seconds
// (scripts/fuzz sets both) fails the run.
//
// The checkpoint target re-signs every input (its last 8 bytes become the FNV-1a checksum
// of the rest), so that mutations get past the checksum to the header, identity and sum
// checks behind it; a wrong checksum is tested in tests/render/checkpoint_test.cpp.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "fuzz_scratch_dir.h"
#include "util/error.h"
#include "util/input_limits.h"

#if TESSERA_FUZZ_READER == 1
#include "view/camera_path.h"
#elif TESSERA_FUZZ_READER == 2
#include "view/input.h"
#elif TESSERA_FUZZ_READER == 3
#include "render/checkpoint.h"
#elif TESSERA_FUZZ_READER == 4
#include "image/image_io.h"
#else
#error "TESSERA_FUZZ_READER must be 1..4"
#endif

namespace fs = std::filesystem;

namespace {

const fs::path& input_file() {
    static const fs::path file = tessera::fuzz::scratch_dir("-readers") / "input";
    return file;
}

[[noreturn]] void broken(const char* what) {
    std::fprintf(stderr, "input_readers_fuzzer: a read value breaks the reader's promise: %s\n", what);
    std::abort();
}

#if TESSERA_FUZZ_READER == 1
bool finite3(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void read_and_check(const fs::path& p) {
    for (const tessera::view::PathFrame& f : tessera::view::read_camera_path(p)) {
        const tessera::Camera& c = f.camera;
        if (!finite3(c.position) || !finite3(c.look_at) || !finite3(c.up)) broken("a camera is not finite");
        if (!(c.vfov_deg > 0.0f && c.vfov_deg < 180.0f)) broken("a vfov is outside (0, 180)");
        if (f.frame < 0 || f.frame >= tessera::limits::kViewFrames) broken("a frame is out of range");
        if (glm::length(glm::cross(c.look_at - c.position, c.up)) == 0.0f) broken("a view is degenerate");
    }
}
#elif TESSERA_FUZZ_READER == 2
void read_and_check(const fs::path& p) {
    int last = 0;
    for (const tessera::view::ScriptedEvent& s : tessera::view::read_input_script(p)) {
        if (s.frame < last || s.frame >= tessera::limits::kViewFrames) broken("frames unsorted or out of range");
        last = s.frame;
        const auto& e = s.event;
        if (!std::isfinite(e.dx) || !std::isfinite(e.dy) || std::fabs(e.dx) > 1e5f || std::fabs(e.dy) > 1e5f)
            broken("a drag or scroll is not finite or out of range");
    }
}
#elif TESSERA_FUZZ_READER == 3
tessera::RunIdentity identity() {
    tessera::RunIdentity id;
    id.scene_path = "/scenes/box.json";
    id.scene_file_hash = 42;
    id.scene_data_hash = 43;
    id.method = "direct";
    id.seed = 1;
    id.shadow_samples = 8;
    id.width = 4;
    id.height = 3;
    id.backend = "embree";
    return id;
}
void read_and_check(const fs::path& p) {
    tessera::Accumulator acc(4, 3);
    const uint32_t passes = tessera::load_checkpoint(p, identity(), acc);
    if (acc.passes() != passes) broken("the pass count differs from the file's");
    for (double v : acc.sums())
        if (!std::isfinite(v)) broken("a restored sum is not finite");
    for (uint32_t h : acc.hit_counts())
        if (h > passes) broken("more hits than passes");
}
#elif TESSERA_FUZZ_READER == 4
void read_and_check(const fs::path& p) {
    const tessera::Image img = tessera::read_exr(p);
    if (img.width < 1 || img.height < 1 || img.width > tessera::limits::kImageSide ||
        img.height > tessera::limits::kImageSide)
        broken("an image size is out of range");
    for (const auto& c : img.channels)
        if (c.data.size() != size_t(img.width) * size_t(img.height)) broken("a channel's size differs from the image's");
}
#endif

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::vector<char> bytes(data, data + size);
#if TESSERA_FUZZ_READER == 3
    if (size > 8) {
        const uint64_t sum = tessera::fnv1a64(bytes.data(), size - 8);
        std::memcpy(bytes.data() + size - 8, &sum, 8);
    }
#endif
    {
        std::ofstream out(input_file(), std::ios::binary | std::ios::trunc);
        out.write(bytes.data(), std::streamsize(bytes.size()));
    }
    try {
        read_and_check(input_file());
    } catch (const tessera::InputError&) {
        // bad input, reported as such: the expected outcome
    }
    return 0;
}
