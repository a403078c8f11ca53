#include "render/checkpoint.h"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <utility>
#include <system_error>
#include <type_traits>
#include <vector>

#include "image/atomic_file.h"
#include "kernels/shared/layout_pass.h"
#include "util/error.h"

namespace tessera {
namespace fs = std::filesystem;
static_assert(std::endian::native == std::endian::little, "the checkpoint format is little-endian");

namespace {

constexpr char kMagic[8] = {'T', 'S', 'C', 'K', 'P', 'T', '0', '1'};
// 2: the method's other settings in the identity (2026-11-29); pt's --max-depth counts
// one more emitter hit. 3: the method's own sums (the igi family's --aov channels).
// 4: the same layout; the igi family's passes changed (the filter's window at the image
// border, the clamp's length D), so their older checkpoints are refused (pt's and
// direct's still load).
constexpr uint32_t kVersion = 4;
constexpr uint32_t kIgiFamilyVersion = 4;  // the oldest an igi-family run resumes from

// The methods whose passes changed in format 4: the igi family of that day, a fixed fact
// of the format's history (not igi_family(), which would also tie the checkpoint reader,
// and its fuzzer, to the method table).
bool passes_changed_in_format_4(const std::string& method) {
    for (const char* m : {"igi", "ais", "ais-max", "ic", "tic"})
        if (method == m) return true;
    return false;
}
constexpr uint32_t kOldestVersion = 2;  // read too: the same but for the method's sums
constexpr uint32_t kMaxString = 1u << 16;
constexpr uint32_t kMaxMethodSums = 64;  // AIS keeps 14; a bound for a corrupt count

/// Bytes in memory (the identity record), in the file's encoding.
struct Bytes {
    std::vector<char> b;
    void raw(const void* p, std::size_t n) {
        const std::size_t at = b.size();
        b.resize(at + n);
        if (n) std::memcpy(b.data() + at, p, n);
    }
    template <class T> void put(T v) { raw(&v, sizeof v); }
    void put(const std::string& s) {
        put(uint32_t(s.size()));
        raw(s.data(), s.size());
    }
};

Bytes identity_bytes(const RunIdentity& id) {
    Bytes r;
    r.put(id.scene_path);
    r.put(id.scene_file_hash);
    r.put(id.scene_data_hash);
    r.put(id.method);
    r.put(id.seed);
    r.put(id.shadow_samples);
    r.put(id.max_depth);
    r.put(id.max_scatter);
    r.put(id.width);
    r.put(id.height);
    r.put(id.backend);
    r.put(id.method_settings);
    return r;
}

uint64_t identity_hash(const RunIdentity& id) {
    Bytes b = identity_bytes(id);
    return fnv1a64(b.b.data(), b.b.size());
}

/// Sequential reads from the checkpoint file, hashing every byte read.
struct Reader {
    std::ifstream in;
    std::string name;
    uint64_t hash = fnv1a64(nullptr, 0);

    [[noreturn]] void fail(const std::string& what) const { throw InputError("checkpoint " + name + ": " + what); }
    void raw(void* dst, std::size_t n) {
        if (!in.read(static_cast<char*>(dst), std::streamsize(n))) fail("truncated (file ends early)");
        hash = fnv1a64(dst, n, hash);
    }
    template <class T> T get() {
        T v;
        raw(&v, sizeof v);
        return v;
    }
    std::string str() {
        const uint32_t n = get<uint32_t>();
        if (n > kMaxString) fail("corrupt (string of " + std::to_string(n) + " bytes)");
        std::string s(n, '\0');
        raw(s.data(), n);
        return s;
    }
    template <class T> std::vector<T> array(std::size_t n) {
        std::vector<T> v(n);
        raw(v.data(), n * sizeof(T));
        return v;
    }
};

/// A checksum only says the file is what was written; the sums must also be finite (a
/// NaN or Inf would reach every pixel written from them) and the squares non-negative.
void check_sums(const Reader& r, int32_t width, const std::vector<double>& v, std::size_t per_pixel,
                const char* what, bool squares = false) {
    for (std::size_t i = 0; i < v.size(); ++i)
        if (!std::isfinite(v[i]) || (squares && v[i] < 0.0)) {
            const std::size_t pixel = i / per_pixel;
            r.fail("corrupt (" + std::string(std::isfinite(v[i]) ? "negative" : std::isnan(v[i]) ? "NaN" : "infinite") +
                   " " + what + " at pixel (" + std::to_string(pixel % std::size_t(width)) + ", " +
                   std::to_string(pixel / std::size_t(width)) + ")); delete it to render from the start");
        }
}

// RunIdentity::method_settings as (option, value) pairs.
std::vector<std::pair<std::string, std::string>> setting_pairs(const std::string& text) {
    std::vector<std::pair<std::string, std::string>> out;
    std::istringstream in(text);
    std::string option, value;
    while (in >> option >> value) out.emplace_back(option, value);
    return out;
}

// "<head>--tile 3, this run has --tile 5" for the first method setting that differs.
std::string differs_in_settings(const std::string& head, const std::string& saved, const std::string& now) {
    if (saved == now) return "";
    const auto a = setting_pairs(saved), b = setting_pairs(now);
    for (const auto& [option, value] : a)
        for (const auto& [option_now, value_now] : b)
            if (option == option_now && value != value_now)
                return head + option + " " + value + ", this run has " + option + " " + value_now;
    return head + "the settings \"" + saved + "\", this run has \"" + now + "\"";
}

/// "checkpoint X was made with --seed 1, this run has --seed 2" for the first field of
/// the identity that differs ("" if none does).
std::string describe_difference(const std::string& name, const RunIdentity& saved, const RunIdentity& now) {
    const std::string head = "checkpoint " + name + " was made with ";
    auto differs = [&](const char* option, const auto& a, const auto& b) -> std::string {
        if (a == b) return "";
        auto text = [](const auto& v) {
            if constexpr (std::is_convertible_v<decltype(v), std::string>) return std::string(v);
            else return std::to_string(v);
        };
        return head + option + " " + text(a) + ", this run has " + option + " " + text(b);
    };
    auto scene = [](const std::string& p) { return p.empty() ? std::string("(built in code)") : p; };
    if (saved.scene_path != now.scene_path)
        return head + "scene " + scene(saved.scene_path) + ", this run has scene " + scene(now.scene_path);
    if (saved.scene_file_hash != now.scene_file_hash || saved.scene_data_hash != now.scene_data_hash)
        return "checkpoint " + name + " was made from different scene data: " +
               (saved.scene_file_hash != now.scene_file_hash ? "the scene file " + now.scene_path
                                                             : std::string("a mesh, material or texture")) +
               " has changed since";
    for (const std::string& s : {differs("--method", saved.method, now.method),
                                 differs("--seed", saved.seed, now.seed),
                                 differs("--shadow-samples", saved.shadow_samples, now.shadow_samples),
                                 differs("--max-depth", saved.max_depth, now.max_depth),
                                 differs("--max-scatter", saved.max_scatter, now.max_scatter),
                                 differs("--width", saved.width, now.width),
                                 differs("--height", saved.height, now.height),
                                 differs("--backend", saved.backend, now.backend)})
        if (!s.empty()) return s;
    return differs_in_settings(head, saved.method_settings, now.method_settings);
}

}  // namespace

fs::path checkpoint_path_for(const fs::path& out) {
    fs::path p = out;
    return p.replace_extension(".ckpt");
}

void save_checkpoint(const fs::path& path, const RunIdentity& id, uint32_t spp_target, const Accumulator& acc,
                     const std::vector<const std::vector<double>*>& method_sums) {
    Bytes head;
    head.raw(kMagic, sizeof kMagic);
    head.put(kVersion);
    head.put(uint32_t(TS_PASS_FLOATS));
    head.put(int32_t(acc.width()));
    head.put(int32_t(acc.height()));
    head.put(acc.passes());
    head.put(spp_target);
    head.put(identity_hash(id));
    const Bytes ident = identity_bytes(id);
    head.raw(ident.b.data(), ident.b.size());
    head.put(uint32_t(method_sums.size()));
    for (const std::vector<double>* m : method_sums) head.put(uint64_t(m->size()));

    replace_file_atomic(path, [&](const fs::path& temp) {
        errno = 0;  // what the failing write leaves, for the message
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        uint64_t h = fnv1a64(nullptr, 0);
        auto write = [&](const void* p, std::size_t n) {
            out.write(static_cast<const char*>(p), std::streamsize(n));
            h = fnv1a64(p, n, h);
        };
        write(head.b.data(), head.b.size());
        write(acc.sums().data(), acc.sums().size() * sizeof(double));
        write(acc.sums_of_squares().data(), acc.sums_of_squares().size() * sizeof(double));
        write(acc.hit_counts().data(), acc.hit_counts().size() * sizeof(uint32_t));
        for (const std::vector<double>* m : method_sums) write(m->data(), m->size() * sizeof(double));
        out.write(reinterpret_cast<const char*>(&h), sizeof h);
        out.close();
        if (!out) {
            const int err = errno;
            throw RuntimeError("cannot write checkpoint " + path.string() + ": write failed" +
                               (err ? std::string(": ") + std::strerror(err) : std::string()));
        }
    });
}

namespace {

/// A checkpoint's header, up to the pixel data, with the sizes it implies.
struct Header {
    uint32_t version = 0;
    int32_t width = 0, height = 0;
    uint32_t passes = 0;
    uint64_t settings_hash = 0;
    RunIdentity saved;
    std::vector<uint64_t> method_lengths;  ///< values in each method sum array
    std::size_t pixels = 0;
};

/// Reads the header from r (at the file's start) and checks the magic, the version, the
/// sizes and that the file's length is the one they give.
Header read_header(Reader& r, const fs::path& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec) || !r.in) r.fail("cannot be read (missing or not a file)");
    const uintmax_t file_size = fs::file_size(path, ec);

    Header hd;
    char magic[8];
    r.raw(magic, sizeof magic);
    if (std::memcmp(magic, kMagic, 6) != 0) r.fail("not a Tessera checkpoint (bad magic)");
    hd.version = r.get<uint32_t>();
    if (std::memcmp(magic, kMagic, sizeof magic) != 0 || hd.version < kOldestVersion || hd.version > kVersion)
        r.fail("format version " + std::to_string(hd.version) + " is not supported (this build reads versions " +
               std::to_string(kOldestVersion) + " to " + std::to_string(kVersion) + ")");
    if (r.get<uint32_t>() != TS_PASS_FLOATS) r.fail("corrupt (floats per pixel differ from this build's)");
    const int32_t w = r.get<int32_t>(), h = r.get<int32_t>();
    if (w < 1 || h < 1 || w > 16384 || h > 16384) r.fail("corrupt (image size out of range)");
    hd.width = w, hd.height = h;
    hd.passes = r.get<uint32_t>();
    r.get<uint32_t>();  // spp target of the saving run: informational
    hd.settings_hash = r.get<uint64_t>();
    RunIdentity& saved = hd.saved;
    saved.scene_path = r.str();
    saved.scene_file_hash = r.get<uint64_t>();
    saved.scene_data_hash = r.get<uint64_t>();
    saved.method = r.str();
    saved.seed = r.get<uint32_t>();
    saved.shadow_samples = r.get<uint32_t>();
    saved.max_depth = r.get<uint32_t>();
    saved.max_scatter = r.get<uint32_t>();
    saved.width = r.get<int32_t>();
    saved.height = r.get<int32_t>();
    saved.backend = r.str();
    saved.method_settings = r.str();

    const std::size_t n = hd.pixels = std::size_t(w) * std::size_t(h);
    const uint32_t method_count = hd.version >= 3 ? r.get<uint32_t>() : 0;
    if (method_count > kMaxMethodSums) r.fail("corrupt (" + std::to_string(method_count) + " method sum arrays)");
    hd.method_lengths.resize(method_count);
    uintmax_t method_bytes = 0;
    for (uint64_t& len : hd.method_lengths) {
        len = r.get<uint64_t>();
        // One or three values a pixel (guidance, components), or none yet.
        if (len != 0 && len != n && len != 3 * n) r.fail("corrupt (a method sum of " + std::to_string(len) + " values)");
        method_bytes += len * 8;
    }
    const uintmax_t expected = uintmax_t(r.in.tellg()) + n * (TS_PASS_FLOATS * 8 + 3 * 8 + 4) + method_bytes + 8;
    if (ec || file_size != expected)
        r.fail("truncated or corrupt (" + std::to_string(file_size) + " bytes, expected " + std::to_string(expected) +
               " for " + std::to_string(w) + "x" + std::to_string(h) + ")");
    return hd;
}

/// The checksum, after the data r has hashed so far, and the header's own consistency.
void check_checksum(Reader& r, const Header& hd) {
    const uint64_t computed = r.hash;
    if (r.get<uint64_t>() != computed) r.fail("corrupt (checksum mismatch)");
    if (hd.saved.width != hd.width || hd.saved.height != hd.height || hd.settings_hash != identity_hash(hd.saved))
        r.fail("corrupt (header fields disagree)");
}

}  // namespace

void check_checkpoint_file(const fs::path& path) {
    Reader r{std::ifstream(path, std::ios::binary), path.string()};
    const Header hd = read_header(r, path);
    // The pixel data in pieces, for the checksum only: the whole checkpoint of a large
    // image is not held twice.
    std::error_code ec;
    uintmax_t left = fs::file_size(path, ec) - uintmax_t(r.in.tellg()) - 8;
    std::vector<char> piece(std::size_t(1) << 20);
    while (left > 0) {
        const std::size_t k = std::size_t(std::min<uintmax_t>(left, piece.size()));
        r.raw(piece.data(), k);
        left -= k;
    }
    check_checksum(r, hd);
}

uint32_t load_checkpoint(const fs::path& path, const RunIdentity& id, Accumulator& acc, MethodSums* method_sums,
                         uint32_t* format_version) {
    Reader r{std::ifstream(path, std::ios::binary), path.string()};
    const Header hd = read_header(r, path);
    if (format_version) *format_version = hd.version;
    const int32_t w = hd.width, h = hd.height;
    const uint32_t passes = hd.passes, version = hd.version;
    const RunIdentity& saved = hd.saved;
    const std::size_t n = hd.pixels;
    std::vector<double> sums = r.array<double>(n * TS_PASS_FLOATS);
    std::vector<double> sums_sq = r.array<double>(n * 3);
    std::vector<uint32_t> hits = r.array<uint32_t>(n);
    MethodSums method;
    for (uint64_t len : hd.method_lengths) method.push_back(r.array<double>(std::size_t(len)));
    check_checksum(r, hd);
    check_sums(r, w, sums, TS_PASS_FLOATS, "sum");
    check_sums(r, w, sums_sq, 3, "sum of squares", true);
    for (const std::vector<double>& m : method) check_sums(r, w, m, m.size() / n, "method sum");
    for (std::size_t i = 0; i < n; ++i)
        if (hits[i] > passes)
            r.fail("corrupt (pixel (" + std::to_string(i % std::size_t(w)) + ", " + std::to_string(i / std::size_t(w)) +
                   ") has more hits than passes); delete it to render from the start");

    if (version < kIgiFamilyVersion && saved.method == id.method && passes_changed_in_format_4(id.method))
        throw InputError("checkpoint " + r.name + " was made by an older build, whose --method " + id.method +
                         " passes differ from this build's (the filter at the image border, the VPL clamp's "
                         "length): delete it to render from the start");
    if (hd.settings_hash != identity_hash(id) || !(saved == id)) {
        const std::string what = describe_difference(r.name, saved, id);
        throw InputError(what.empty() ? "checkpoint " + r.name + " was made with different settings" : what);
    }
    if (acc.width() != w || acc.height() != h) r.fail("image size differs from the accumulator's");
    acc.restore(passes, std::move(sums), std::move(sums_sq), std::move(hits));
    if (method_sums) *method_sums = std::move(method);
    return passes;
}

}  // namespace tessera
