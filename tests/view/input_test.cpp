// Input scripts (--input-script): parsed events by frame, and one clear message naming
// the file and the entry for a bad one.
#include "view/input.h"

#include <fstream>

#include <gtest/gtest.h>

#include "scene/scene_test_util.h"
#include "support/scratch_dir.h"
#include "util/error.h"

namespace tessera::view {
namespace {

class InputScript : public test::ScratchDirTest {
protected:
    std::filesystem::path write(const std::string& text) {
        const auto p = dir_ / "script.json";
        std::ofstream(p) << text;
        return p;
    }
    std::string error_of(const std::string& text) {
        try {
            read_input_script(write(text));
        } catch (const InputError& e) {
            return e.what();
        }
        return "";
    }
};

TEST(InputKeys, CodesOfKeyNames) {
    EXPECT_EQ(key_code("w"), 'W');
    EXPECT_EQ(key_code("W"), 'W');
    EXPECT_EQ(key_code("["), '[');
    EXPECT_EQ(key_code("space"), ' ');
    EXPECT_EQ(key_code("escape"), kKeyEscape);
    EXPECT_EQ(key_code("ww"), -1);
    EXPECT_EQ(key_code(""), -1);
}

TEST_F(InputScript, ReadsEventsSortedByFrame) {
    const auto events = read_input_script(write(R"({"events": [
        {"frame": 5, "release": "w"}, {"frame": 0, "press": "w"}, {"frame": 6, "drag": [10, -2.5]},
        {"frame": 7, "scroll": -1}, {"frame": 8, "tap": "p"}, {"frame": 9, "quit": true}]})"));
    using K = InputEvent::Kind;
    ASSERT_EQ(events.size(), 7u);  // the tap is a press and a release
    EXPECT_EQ(events[0].frame, 0);
    EXPECT_EQ(events[0].event.kind, K::Press);
    EXPECT_EQ(events[0].event.key, 'W');
    EXPECT_EQ(events[1].event.kind, K::Release);
    EXPECT_EQ(events[2].event.kind, K::Drag);
    EXPECT_EQ(events[2].event.dx, 10.0f);
    EXPECT_EQ(events[2].event.dy, -2.5f);
    EXPECT_EQ(events[3].event.dy, -1.0f);
    EXPECT_EQ(events[4].event.kind, K::Press);
    EXPECT_EQ(events[5].event.kind, K::Release);
    EXPECT_EQ(events[5].event.key, 'P');
    EXPECT_EQ(events[6].event.kind, K::Quit);
}

TEST_F(InputScript, RejectsBadEntriesNamingThem) {
    EXPECT_CONTAINS(error_of("{"), "not valid JSON");
    EXPECT_CONTAINS(error_of(R"({"ev": []})"), "\"events\"");
    EXPECT_CONTAINS(error_of(R"({"events": [{"press": "w"}]})"), "events[0]: needs \"frame\"");
    EXPECT_CONTAINS(error_of(R"({"events": [{"frame": 1, "press": "w"}, {"frame": -1, "press": "w"}]})"), "events[1]");
    EXPECT_CONTAINS(error_of(R"({"events": [{"frame": 1, "press": "up"}]})"), "\"up\"");
    EXPECT_CONTAINS(error_of(R"({"events": [{"frame": 1, "drag": [1]}]})"), "[dx, dy]");
    EXPECT_CONTAINS(error_of(R"({"events": [{"frame": 1, "jump": 1}]})"), "needs one of");
    try {
        read_input_script(dir_ / "missing.json");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_CONTAINS(e.what(), "--input-script");
        EXPECT_CONTAINS(e.what(), "missing.json");
    }
}

}  // namespace
}  // namespace tessera::view
