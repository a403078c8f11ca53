// bench/flicker end to end on a tiny fly-through (32x32, 3 frames held 4 times, Embree):
// a fog scene reports SS, ID, PM and the image, a clear one no PM, each figure positive,
// finite and below 2 (relative to the component's own level), and the table names them.
#include <cmath>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/scratch_dir.h"
#include "support/shell.h"

namespace fs = std::filesystem;
using tessera::test::shell_status;

namespace {

class Flicker : public tessera::test::ScratchDirTest {};

}  // namespace

TEST_F(Flicker, TinyFlyThroughReportsEachComponent) {
    const std::string src = TESSERA_SOURCE_DIR;
    const fs::path out = dir_ / "out", log = dir_ / "log.txt";
    fs::create_directories(out);
    const std::string cmd = "python3 " + src + "/bench/flicker --build " + fs::path(TESSERA_EXE).parent_path().string() +
                            " --scenes cornell-box-fog,cornell-box --methods igi --size 32 --frames 3 --hold 4 --out " +
                            out.string() + " > " + log.string() + " 2>&1";
    ASSERT_EQ(shell_status(cmd), 0) << std::ifstream(log).rdbuf();
    const nlohmann::json doc = nlohmann::json::parse(std::ifstream(out / "flicker.json"));
    ASSERT_EQ(doc["rows"].size(), 2u);
    const auto& fog = doc["rows"][0]["components"];
    const auto& clear = doc["rows"][1]["components"];
    for (const char* c : {"SS", "ID", "PM", "image"}) {
        ASSERT_TRUE(fog.contains(c)) << c;
        for (const char* k : {"flicker", "noise"}) {
            const double v = fog[c][k].get<double>();
            EXPECT_TRUE(std::isfinite(v) && v > 0.0) << c << " " << k << " " << v;
            EXPECT_LT(v, 2.0) << c << " " << k << ": relative to the component's own level";
        }
    }
    EXPECT_FALSE(clear.contains("PM")) << "no medium, no PM component";
    EXPECT_TRUE(clear.contains("SS") && clear.contains("ID"));
    std::ifstream md(out / "flicker.md");
    const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("| cornell-box-fog | igi | PM |"), std::string::npos) << text;
}
