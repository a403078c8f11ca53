// Shared helpers for the scene loader tests.
#pragma once
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <glm/glm.hpp>
#include <zlib.h>  // crc32, through libpng's link

#include "scene/loader.h"
#include "util/error.h"

namespace tessera::test {

/// A file in tests/data.
inline std::filesystem::path fixture(const std::string& name) {
    return std::filesystem::path(TESSERA_TEST_DATA) / name;
}

/// A scratch directory path unique to this process and test, so tests that CTest runs
/// in parallel never share files. The caller creates and removes it.
inline std::filesystem::path unique_temp_dir(const std::string& tag) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "-" + info->name();
    for (char& c : name)
        if (c == '/') c = '-';
    return std::filesystem::temp_directory_path() / (tag + "-" + std::to_string(::getpid()) + "-" + name);
}

/// The bytes of `file`, whole ("" if it cannot be read).
inline std::string read_bytes(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// A PNG chunk as it sits in the file: big-endian length, type, data and the CRC-32 of
/// type and data (PNG spec, 5.3), which libpng checks.
inline std::string png_chunk(const std::string& type, const std::string& data) {
    const std::string body = type + data;
    const auto crc = static_cast<uint32_t>(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size())));
    auto be = [](uint32_t v) { return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; };
    return be(static_cast<uint32_t>(data.size())) + body + be(crc);
}

/// Geometric normal of triangle i, cross(p1 - p0, p2 - p0), normalised.
inline glm::vec3 geometric_normal(const Scene& s, size_t i) {
    return glm::normalize(glm::cross(s.positions[3 * i + 1] - s.positions[3 * i],
                                     s.positions[3 * i + 2] - s.positions[3 * i]));
}

/// Asserts that `text` contains `part` (gmock's HasSubstr is not linked here).
#define EXPECT_CONTAINS(text, part)                                                   \
    EXPECT_NE(std::string(text).find(part), std::string::npos)                        \
        << "expected \"" << (text) << "\" to contain \"" << (part) << "\""

/// The message of the InputError that loading `scene_file` throws ("" if none).
inline std::string load_error(const std::filesystem::path& scene_file,
                              const DataPath& data = DataPath{}) {
    try {
        load_scene(scene_file, data);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace tessera::test
