// Checkpoints: the saved accumulator comes back bit for bit, a bad or foreign file is
// refused naming the file and what differs, and a render interrupted by SIGINT and
// resumed gives exactly the image of an uninterrupted render.
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <iterator>
#include <limits>
#include <optional>

#include <gtest/gtest.h>

#include "support/scratch_dir.h"

#include "kernels/shared/layout_pass.h"
#include "render/checkpoint.h"
#include "render/checkpoint_session.h"
#include "scene/loader.h"
#include "util/error.h"

#include "support/render_helpers.h"
#include "support/test_scenes.h"
#include "kernels/shared/layout_igi.h"

namespace tessera {
namespace {
namespace fs = std::filesystem;

class Checkpoint : public tessera::test::ScratchDirTest {};

// Pseudo-random pass data: finite values, and Z = +inf (a miss) on some pixels.
std::vector<float> synthetic_pass(int w, int h, uint32_t k) {
    std::vector<float> p(size_t(w) * h * TS_PASS_FLOATS);
    uint32_t x = 12345u + 7919u * k;
    for (size_t i = 0; i < p.size(); ++i) {
        x = x * 1664525u + 1013904223u;
        p[i] = float(x >> 8) / float(1 << 24) * 3.0f;
        if (i % TS_PASS_FLOATS == 9 && (x & 3) == 0) p[i] = std::numeric_limits<float>::infinity();
    }
    return p;
}

RunIdentity some_identity(int w, int h) {
    RunIdentity id;
    id.scene_path = "/scenes/box.json";
    id.scene_file_hash = 42;
    id.scene_data_hash = 43;
    id.method = "direct";
    id.seed = 1;
    id.shadow_samples = 8;
    id.width = w;
    id.height = h;
    id.backend = "embree";
    return id;
}

void expect_bit_identical(const Image& a, const Image& b) {
    ASSERT_EQ(a.channels.size(), b.channels.size());
    for (size_t c = 0; c < a.channels.size(); ++c) {
        EXPECT_EQ(a.channels[c].name, b.channels[c].name);
        ASSERT_EQ(a.channels[c].data.size(), b.channels[c].data.size());
        EXPECT_EQ(0, std::memcmp(a.channels[c].data.data(), b.channels[c].data.data(),
                                 a.channels[c].data.size() * sizeof(float)))
            << "channel " << a.channels[c].name << " differs";
    }
}

// Expects `f` to throw InputError whose message contains every one of `needles`.
template <class F> void expect_input_error(F f, std::initializer_list<std::string> needles) {
    try {
        f();
        ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
        for (const auto& n : needles) EXPECT_NE(std::string(e.what()).find(n), std::string::npos) << e.what();
    }
}

TEST_F(Checkpoint, RoundTripIsBitIdenticalAndContinues) {
    const int w = 7, h = 5;
    Accumulator a(w, h);
    for (uint32_t k = 0; k < 9; ++k) a.add(synthetic_pass(w, h, k));
    const fs::path file = dir_ / "x.ckpt";
    save_checkpoint(file, some_identity(w, h), 20, a);
    Accumulator b(w, h);
    EXPECT_EQ(load_checkpoint(file, some_identity(w, h), b), 9u);
    EXPECT_EQ(b.passes(), 9u);
    EXPECT_EQ(a.sums(), b.sums());
    EXPECT_EQ(a.hit_counts(), b.hit_counts());
    expect_bit_identical(a.mean_image(true, true), b.mean_image(true, true));
    a.add(synthetic_pass(w, h, 9));
    b.add(synthetic_pass(w, h, 9));
    expect_bit_identical(a.mean_image(true, true), b.mean_image(true, true));
}

// Applies `edit` to a checkpoint's bytes, then re-signs it (the checksum of the rest).
void rewrite(const fs::path& file, const std::function<void(std::vector<char>&)>& edit) {
    std::ifstream in(file, std::ios::binary);
    std::vector<char> b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    in.close();
    edit(b);
    const uint64_t sum = fnv1a64(b.data(), b.size() - 8);
    std::memcpy(b.data() + b.size() - 8, &sum, 8);
    std::ofstream(file, std::ios::binary | std::ios::trunc).write(b.data(), std::streamsize(b.size()));
}

// Rewrites a format-3 checkpoint of `pixels` pixels saved without method sums (K = 0, no
// lengths) as the format-2 file an older build wrote: version 2, no K, re-signed.
void to_format_2(const fs::path& file, size_t pixels) {
    rewrite(file, [&](std::vector<char>& b) {
        const size_t k_at = b.size() - 8 - pixels * (TS_PASS_FLOATS * 8 + 3 * 8 + 4) - 4;
        uint32_t k = 1, version = 2;
        std::memcpy(&k, b.data() + k_at, 4);
        ASSERT_EQ(k, 0u) << "only a checkpoint without method sums has a format-2 twin";
        b.erase(b.begin() + std::ptrdiff_t(k_at), b.begin() + std::ptrdiff_t(k_at) + 4);
        std::memcpy(b.data() + 8, &version, 4);
    });
}

// A format-2 checkpoint (before the method's sums were kept) still loads: the same sums,
// no method sums, its version said.
TEST_F(Checkpoint, Format2StillLoads) {
    const int w = 4, h = 3;
    Accumulator a(w, h);
    a.add(synthetic_pass(w, h, 0));
    const fs::path file = dir_ / "x.ckpt";
    save_checkpoint(file, some_identity(w, h), 4, a);
    to_format_2(file, size_t(w) * h);
    Accumulator b(w, h);
    MethodSums restored{{1.0}};
    uint32_t version = 0;
    EXPECT_EQ(load_checkpoint(file, some_identity(w, h), b, &restored, &version), 1u);
    EXPECT_EQ(version, 2u);
    EXPECT_TRUE(restored.empty());
    EXPECT_EQ(b.sums(), a.sums());
}

// Rewrites a checkpoint's format version as `version` (the layout of 3 and 4 is the same).
void set_version(const fs::path& file, uint32_t version) {
    rewrite(file, [&](std::vector<char>& b) { std::memcpy(b.data() + 8, &version, 4); });
}

// A format-3 checkpoint holds passes of the igi family from before its filter's border
// windows and clamp length changed: an igi run refuses it (resumed, it would mix two
// estimators in one image), a direct run (unchanged) still loads its own.
TEST_F(Checkpoint, Format3OfTheIgiFamilyIsRefused) {
    const int w = 4, h = 3;
    Accumulator a(w, h);
    a.add(synthetic_pass(w, h, 0));
    for (const char* method : {"igi", "direct"}) {
        RunIdentity id = some_identity(w, h);
        id.method = method;
        const fs::path file = dir_ / (std::string(method) + ".ckpt");
        save_checkpoint(file, id, 4, a);
        set_version(file, 3);
        Accumulator b(w, h);
        if (std::string(method) == "direct") {
            EXPECT_EQ(load_checkpoint(file, id, b), 1u);
            continue;
        }
        try {
            load_checkpoint(file, id, b);
            ADD_FAILURE() << "an igi checkpoint of format 3 loaded";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("was made by an older build, whose --method igi passes differ"),
                      std::string::npos)
                << e.what();
        }
    }
}

// The method's sums come back as saved; a checkpoint without them restores none.
TEST_F(Checkpoint, MethodSumsRoundTrip) {
    const int w = 4, h = 3;
    Accumulator a(w, h);
    a.add(synthetic_pass(w, h, 0));
    const std::vector<double> components{0.5, 1.25, 3.0, 0.0, 7.5, 1e-300, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0,
                                         0.5, 1.25, 3.0, 0.0, 7.5, 1e-300, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0,
                                         1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0, 12.0};
    const std::vector<double> none, guidance(size_t(w) * h, 0.25);
    const fs::path file = dir_ / "x.ckpt";
    save_checkpoint(file, some_identity(w, h), 4, a, {&components, &none, &guidance});
    Accumulator b(w, h);
    MethodSums restored{{9.0}};
    EXPECT_EQ(load_checkpoint(file, some_identity(w, h), b, &restored), 1u);
    ASSERT_EQ(restored.size(), 3u);
    EXPECT_EQ(restored[0], components);
    EXPECT_TRUE(restored[1].empty());
    EXPECT_EQ(restored[2], guidance);
    save_checkpoint(file, some_identity(w, h), 4, a);
    EXPECT_EQ(load_checkpoint(file, some_identity(w, h), b, &restored), 1u);
    EXPECT_TRUE(restored.empty());
    // A method sum that is not 1 or 3 values a pixel is corrupt.
    const std::vector<double> odd(5, 1.0);
    save_checkpoint(file, some_identity(w, h), 4, a, {&odd});
    expect_input_error([&] { load_checkpoint(file, some_identity(w, h), b, &restored); },
                       {file.string(), "a method sum of 5 values"});
}

TEST_F(Checkpoint, CorruptTruncatedOrMissingFileIsInputErrorNamingIt) {
    const int w = 4, h = 4;
    Accumulator a(w, h);
    a.add(synthetic_pass(w, h, 0));
    const fs::path file = dir_ / "x.ckpt";
    save_checkpoint(file, some_identity(w, h), 4, a);
    const auto good_size = fs::file_size(file);
    auto load = [&] {
        Accumulator b(w, h);
        load_checkpoint(file, some_identity(w, h), b);
    };
    auto poke = [&](std::streamoff at, char byte) {
        std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(at);
        f.put(byte);
    };

    // check_checkpoint_file (the render command's check before its set-up) finds the same.
    auto check = [&] { check_checkpoint_file(file); };
    EXPECT_NO_THROW(check());
    for (const auto& read : {std::function<void()>(load), std::function<void()>(check)}) {
        fs::resize_file(file, good_size - 3);
        expect_input_error(read, {file.string(), "truncated"});
        fs::resize_file(file, 20);
        expect_input_error(read, {file.string(), "truncated"});

        save_checkpoint(file, some_identity(w, h), 4, a);
        poke(std::streamoff(good_size / 2), 0x55);  // inside the sums
        expect_input_error(read, {file.string(), "checksum"});

        save_checkpoint(file, some_identity(w, h), 4, a);
        poke(0, 'X');
        expect_input_error(read, {file.string(), "magic"});

        save_checkpoint(file, some_identity(w, h), 4, a);
        poke(7, '2');  // "TSCKPT02"
        expect_input_error(read, {file.string(), "version"});

        fs::remove(file);
        expect_input_error(read, {file.string()});
        save_checkpoint(file, some_identity(w, h), 4, a);
    }
}

// The early check reads a large checkpoint in 1 MiB pieces: a byte changed in the last
// piece still fails its checksum, and an intact file passes.
TEST_F(Checkpoint, FileCheckCoversEveryPieceOfALargeCheckpoint) {
    const int w = 300, h = 200;  // ~10 MB of sums
    Accumulator a(w, h);
    a.add(synthetic_pass(w, h, 0));
    const fs::path file = dir_ / "big.ckpt";
    save_checkpoint(file, some_identity(w, h), 4, a);
    ASSERT_GT(fs::file_size(file), uintmax_t(3) << 20);
    EXPECT_NO_THROW(check_checkpoint_file(file));
    {
        std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(std::streamoff(fs::file_size(file) - 20));  // the hit counts, before the checksum
        f.put(0x55);
    }
    expect_input_error([&] { check_checkpoint_file(file); }, {file.string(), "checksum"});
}

// A file whose checksum is right but whose sums are not usable (a NaN, an Inf, a negative
// square, more hits than passes) is refused before the accumulator is touched.
TEST_F(Checkpoint, NonFiniteSumsWithAValidChecksumAreRefused) {
    const int w = 4, h = 3;
    const size_t n = size_t(w) * h;
    Accumulator a(w, h);
    a.add(synthetic_pass(w, h, 0));
    const fs::path file = dir_ / "x.ckpt";
    // Replaces the bytes at `from_end` bytes before the checksum and re-signs the file.
    auto forge = [&](size_t from_end, const void* bytes, size_t size) {
        save_checkpoint(file, some_identity(w, h), 4, a);
        std::ifstream in(file, std::ios::binary);
        std::vector<char> b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::memcpy(b.data() + b.size() - 8 - from_end, bytes, size);
        const uint64_t sum = fnv1a64(b.data(), b.size() - 8);
        std::memcpy(b.data() + b.size() - 8, &sum, 8);
        std::ofstream(file, std::ios::binary | std::ios::trunc).write(b.data(), std::streamsize(b.size()));
    };
    const size_t hits = 4 * n, squares = hits + 3 * 8 * n, sums = squares + TS_PASS_FLOATS * 8 * n;
    struct Case {
        size_t from_end;
        double value;
        const char* what;
    };
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    for (const Case& c : {Case{sums, nan, "NaN sum at pixel (0, 0)"}, Case{sums - 8 * TS_PASS_FLOATS * 5, inf,
                                                                         "infinite sum at pixel (1, 1)"},
                          Case{squares, -1.0, "negative sum of squares at pixel (0, 0)"}}) {
        forge(c.from_end, &c.value, sizeof c.value);
        Accumulator b(w, h);
        const auto before = b.sums();
        expect_input_error([&] { load_checkpoint(file, some_identity(w, h), b); }, {file.string(), c.what});
        EXPECT_EQ(b.passes(), 0u);
        EXPECT_EQ(b.sums(), before);
    }
    const uint32_t many = 7;
    forge(hits, &many, sizeof many);
    Accumulator b(w, h);
    expect_input_error([&] { load_checkpoint(file, some_identity(w, h), b); }, {file.string(), "more hits than passes"});
}

TEST_F(Checkpoint, DifferentSettingsAreNamed) {
    const int w = 4, h = 4;
    Accumulator a(w, h);
    a.add(synthetic_pass(w, h, 0));
    const fs::path file = dir_ / "x.ckpt";
    save_checkpoint(file, some_identity(w, h), 4, a);
    auto load_with = [&](RunIdentity id) {
        return [&file, id] {
            Accumulator b(id.width, id.height);
            load_checkpoint(file, id, b);
        };
    };
    RunIdentity id = some_identity(w, h);
    id.seed = 2;
    expect_input_error(load_with(id), {"checkpoint " + file.string(), "made with --seed 1, this run has --seed 2"});
    id = some_identity(w, h);
    id.shadow_samples = 3;
    expect_input_error(load_with(id), {file.string(), "--shadow-samples 8", "--shadow-samples 3"});
    id = some_identity(w, h);
    id.backend = "opencl";
    expect_input_error(load_with(id), {file.string(), "--backend embree", "--backend opencl"});
    id = some_identity(w, 8);
    expect_input_error(load_with(id), {file.string(), "--height 4", "--height 8"});
    id = some_identity(w, h);
    id.scene_file_hash = 7;
    expect_input_error(load_with(id), {file.string(), "scene file /scenes/box.json has changed"});
    id = some_identity(w, h);
    id.scene_path = "/other.json";
    expect_input_error(load_with(id), {file.string(), "/scenes/box.json", "/other.json"});
}

// Every setting a method reads is in the identity, and is named when it differs: a
// resume that mixed passes of --tile 3 and --tile 5 (or of two path-subset counts, or of
// a changed mirror reflectance) would give neither run's image.
TEST_F(Checkpoint, MethodSettingsAndMaterialsAreNamed) {
    const int w = 4, h = 4;
    const Scene s = test::closed_box({-1, 0, -1}, {1, 2, 1}, glm::vec3(0.5f), glm::vec3(1.0f), 0.3f);
    RenderSettings igi;
    igi.method = Method::Igi;
    igi.spp = 16;
    const RunIdentity saved = make_run_identity(s, igi, w, h, BackendKind::Embree);
    Accumulator a(w, h);
    a.add(synthetic_pass(w, h, 0));
    const fs::path file = dir_ / "x.ckpt";
    save_checkpoint(file, saved, 16, a);
    auto load_with = [&](const Scene& scene, const RenderSettings& rs) {
        const RunIdentity id = make_run_identity(scene, rs, w, h, BackendKind::Embree);
        return [&file, id] {
            Accumulator b(id.width, id.height);
            load_checkpoint(file, id, b);
        };
    };
    RenderSettings more = igi;
    more.spp = 64;  // raising --spp is what resuming is for
    EXPECT_NO_THROW(load_with(s, more)());
    RenderSettings rs = igi;
    rs.igi.tile = 5;
    expect_input_error(load_with(s, rs), {file.string(), "made with --tile 3, this run has --tile 5"});
    rs = igi;
    rs.igi.filter = false;
    expect_input_error(load_with(s, rs), {"made with --no-filter absent, this run has --no-filter given"});
    rs = igi;
    rs.igi.clamp_c = 0.5f;
    expect_input_error(load_with(s, rs), {"this run has --clamp 0.5"});
    rs = igi;
    rs.igi.components = TS_COMPONENT_SS | TS_COMPONENT_ID;
    expect_input_error(load_with(s, rs), {"made with --components ss,id,pm, this run has --components ss,id"});
    rs.igi.components = TS_COMPONENT_SS | TS_COMPONENT_ID | TS_COMPONENT_PM;  // igi has no edge samples
    EXPECT_NO_THROW(load_with(s, rs)());
    rs = igi;
    rs.aovs = true;  // the per-component channels would hold only the resumed passes
    expect_input_error(load_with(s, rs), {"made with --aov absent, this run has --aov given"});
    Scene mirror = s;
    mirror.materials[0].specular = glm::vec3(0.9f);  // MTL Ks: a mirror's reflectance
    expect_input_error(load_with(mirror, igi), {"a mesh, material or texture has changed"});

    // ic's path subsets follow --spp unless given: 8 passes draw 2, 64 draw 4.
    RenderSettings ic;
    ic.method = Method::Ic;
    ic.spp = 8;
    save_checkpoint(file, make_run_identity(s, ic, w, h, BackendKind::Embree), 8, a);
    rs = ic;
    rs.spp = 64;
    expect_input_error(load_with(s, rs), {"made with --ic-subsets 2, this run has --ic-subsets 4"});
    rs.ic.subsets = 2;
    EXPECT_NO_THROW(load_with(s, rs)());

    // Settings a method does not read: pt's albedo, normal and depth are in every pass,
    // and it always reads the finest mip level.
    RenderSettings pt;
    pt.method = Method::PathTrace;
    save_checkpoint(file, make_run_identity(s, pt, w, h, BackendKind::Embree), 8, a);
    rs = pt;
    rs.aovs = true;
    rs.texture_filter = false;
    rs.igi.tile = 5;
    EXPECT_NO_THROW(load_with(s, rs)());
}

// Renders the Cornell box with checkpoints; `interrupt_at` > 0 raises SIGINT from the
// progress callback after that many passes (in total), like a Ctrl-C mid-render.
Image render_ckpt(Backend& backend, const Scene& scene, const SceneBuffers& lights, const RenderSettings& rs,
                  const CheckpointOptions& ck, uint32_t interrupt_at = 0) {
    ProgressFn progress = [&](uint32_t done, uint32_t, double, uint32_t) {
        if (done == interrupt_at) std::raise(SIGINT);
    };
    return render_frame(backend, scene, lights, rs, nullptr, progress, &ck);
}

// The Cornell box on the parameter's backend, and small settings for `method`.
class ResumeCornell : public tessera::test::ScratchDirTest, public ::testing::WithParamInterface<BackendKind> {
protected:
    RenderSettings small(Method method, uint32_t spp) const {
        RenderSettings rs;
        rs.method = method;
        rs.width = rs.height = 16;
        rs.spp = spp;
        rs.shadow_samples = 2;
        return rs;
    }
    const Scene scene = load_scene(default_scene_path(), make_data_path(std::nullopt));
    SceneBuffers buffers = make_scene_buffers(scene);
    std::unique_ptr<Backend> backend = make_backend(BackendOptions{GetParam(), ""}, buffers, plan_effects(scene));
};

TEST_P(ResumeCornell, InterruptedAndResumedRenderIsBitIdentical) {
    const fs::path& dir = dir_;
    RenderSettings rs;
    rs.width = rs.height = 16;
    rs.spp = 7;
    rs.shadow_samples = 2;
    rs.aovs = true;
    const Image whole = render_frame(*backend, scene, buffers, rs);

    CheckpointOptions ck{dir / "cornell.ckpt", GetParam(), false};
    struct sigaction before {};
    sigaction(SIGINT, nullptr, &before);
    try {
        render_ckpt(*backend, scene, buffers, rs, ck, 3);
        ADD_FAILURE() << "not interrupted";
    } catch (const Interrupted& e) {
        EXPECT_EQ(e.passes_done, 3u);
        EXPECT_EQ(e.passes_total, 7u);
        EXPECT_NE(std::string(e.what()).find("interrupted after 3 of 7 spp"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(ck.path.string()), std::string::npos) << e.what();
    }
    struct sigaction after {};
    sigaction(SIGINT, nullptr, &after);
    EXPECT_EQ(before.sa_handler, after.sa_handler) << "the SIGINT handler was not restored";
    ASSERT_TRUE(fs::exists(ck.path));

    // Resume, interrupt once more at pass 5, resume again to the end.
    ck.resume = true;
    EXPECT_THROW(render_ckpt(*backend, scene, buffers, rs, ck, 5), Interrupted);
    RenderStats stats;
    const Image resumed = render_frame(*backend, scene, buffers, rs, &stats, {}, &ck);
    EXPECT_EQ(stats.passes, 2u) << "passes 5 and 6 only";
    expect_bit_identical(whole, resumed);

    // A seed other than the checkpoint's is refused, naming it.
    RenderSettings other = rs;
    other.seed = 2;
    expect_input_error([&] { render_ckpt(*backend, scene, buffers, other, ck); },
                       {ck.path.string(), "--seed 1", "--seed 2"});
    // Fewer spp than the checkpoint holds is refused; more continues it.
    other = rs;
    other.spp = 4;
    expect_input_error([&] { render_ckpt(*backend, scene, buffers, other, ck); }, {"--spp 4"});
}

TEST_P(ResumeCornell, IntervalCheckpointsResumeToTheSameImage) {
    const fs::path& dir = dir_;
    RenderSettings rs;
    rs.width = rs.height = 16;
    rs.spp = 5;
    rs.shadow_samples = 2;
    rs.checkpoint_interval_s = 1e-9;  // after every pass but the last
    CheckpointOptions ck{dir / "cornell.ckpt", GetParam(), false};
    const Image whole = render_ckpt(*backend, scene, buffers, rs, ck);
    ASSERT_TRUE(fs::exists(ck.path));
    Accumulator acc(16, 16);
    EXPECT_EQ(load_checkpoint(ck.path, make_run_identity(scene, rs, 16, 16, GetParam()), acc), 4u);
    ck.resume = true;
    RenderStats stats;
    const Image resumed = render_frame(*backend, scene, buffers, rs, &stats, {}, &ck);
    EXPECT_EQ(stats.passes, 1u);
    expect_bit_identical(whole, resumed);
}

// A periodic checkpoint that cannot be written (here its directory is a file; a full disk
// alike) is a note, not the end of the render: it ended the run and lost every pass.
TEST_P(ResumeCornell, AnUnwritableIntervalCheckpointDoesNotEndTheRender) {
    RenderSettings rs;
    rs.width = rs.height = 16;
    rs.spp = 3;
    rs.shadow_samples = 2;
    const Image plain = render_frame(*backend, scene, buffers, rs);
    std::ofstream(dir_ / "file") << "not a directory";
    rs.checkpoint_interval_s = 1e-9;
    CheckpointOptions ck{dir_ / "file" / "cornell.ckpt", GetParam(), false};
    testing::internal::CaptureStderr();
    const Image img = render_ckpt(*backend, scene, buffers, rs, ck);
    const std::string log = testing::internal::GetCapturedStderr();
    expect_bit_identical(plain, img);
    EXPECT_NE(log.find("tessera: note: cannot write '" + ck.path.string() + "'"), std::string::npos) << log;
    EXPECT_EQ(log.find("cannot write", log.find("the render goes on")), std::string::npos)
        << "said once:\n" << log;
}

// The igi family's own AOV channels (components before and after the filter, AIS's
// guidance and sets) are sums the method keeps beside the accumulator: the checkpoint
// holds them too, so a resumed --aov render has every channel of the uninterrupted one,
// bit for bit. Before they were saved, the resumed channels averaged only the passes
// rendered after the resume (SS, ID and guidance.* differed; R, G, B did not).
TEST_P(ResumeCornell, MethodAovChannelsResumeBitIdentical) {
    RenderSettings rs = small(Method::Ais, 5);
    rs.aovs = true;
    rs.checkpoint_interval_s = 1e-9;  // after every pass but the last
    CheckpointOptions ck{dir_ / "cornell.ckpt", GetParam(), false};
    const Image whole = render_ckpt(*backend, scene, buffers, rs, ck);
    ASSERT_NE(whole.find("guidance.ID"), nullptr);
    ASSERT_NE(whole.find("ID_filtered.R"), nullptr);
    ck.resume = true;
    RenderStats stats;
    const Image resumed = render_frame(*backend, scene, buffers, rs, &stats, {}, &ck);
    EXPECT_EQ(stats.passes, 1u);
    expect_bit_identical(whole, resumed);
}

// A format-2 checkpoint (no method sums) of a method whose passes have not changed since
// (direct) resumes to the same image; one of the igi family, whose passes changed in
// format 4 (the filter's border windows, the clamp's length), is refused, as resuming it
// would mix two estimators in one image.
TEST_P(ResumeCornell, OlderCheckpointsResumeOnlyWhereTheMethodsPassesAreUnchanged) {
    for (Method method : {Method::Direct, Method::Igi}) {
        SCOPED_TRACE(method_name(method));
        RenderSettings rs = small(method, 4);
        rs.checkpoint_interval_s = 1e-9;
        CheckpointOptions ck{dir_ / "cornell.ckpt", GetParam(), false};
        const Image whole = render_frame(*backend, scene, buffers, rs);
        EXPECT_THROW(render_ckpt(*backend, scene, buffers, rs, ck, 2), Interrupted);  // 2 of 4 passes saved
        Accumulator acc(16, 16);
        EXPECT_EQ(load_checkpoint(ck.path, make_run_identity(scene, rs, 16, 16, GetParam()), acc), 2u);
        save_checkpoint(ck.path, make_run_identity(scene, rs, 16, 16, GetParam()), 4, acc);
        to_format_2(ck.path, 16 * 16);
        ck.resume = true;
        if (method == Method::Igi) {
            expect_input_error([&] { render_frame(*backend, scene, buffers, rs, nullptr, {}, &ck); },
                               {ck.path.string(), "was made by an older build, whose --method igi passes differ"});
            continue;
        }
        RenderStats stats;
        expect_bit_identical(whole, render_frame(*backend, scene, buffers, rs, &stats, {}, &ck));
        EXPECT_EQ(stats.passes, 2u) << "passes 2 and 3 rendered after the resume";
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, ResumeCornell, ::testing::Values(BackendKind::Embree, BackendKind::OpenCL));

}  // namespace
}  // namespace tessera
