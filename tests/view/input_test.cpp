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

// Each bad script: the message names the file, the entry's key path and the reason.
TEST_F(InputScript, RejectsBadEntriesNamingThem) {
    struct Case {
        std::string text, key, reason;
    };
    const std::vector<Case> cases = {
        {"{", "script.json:1:", "malformed JSON"},
        {R"({"ev": []})", "'ev'", "known keys here: events"},
        {R"({"events": [{"press": "w"}]})", "'events[0].frame'", "missing"},
        {R"({"events": [{"frame": 1, "press": "w"}, {"frame": -1, "press": "w"}]})", "'events[1].frame' = -1",
         "0..999999"},
        {R"({"events": [{"frame": 4294967296, "quit": true}]})", "'events[0].frame' = 4294967296", "out of range"},
        {R"({"events": [{"frame": 4294967297, "quit": true}]})", "'events[0].frame' = 4294967297", "out of range"},
        {R"({"events": [{"frame": 1, "press": "up"}]})", "'events[0].press' = \"up\"", "one character"},
        {R"({"events": [{"frame": 1, "drag": [1]}]})", "'events[0].drag'", "[dx, dy]"},
        {R"({"events": [{"frame": 1, "drag": [1, 1e6]}]})", "'events[0].drag[1]'", "100000"},
        {R"({"events": [{"frame": 1, "jump": 1}]})", "'events[0].jump'", "known keys here"},
        {R"({"events": [{"frame": 1, "fov": 1, "quit": true}]})", "'events[0].fov'", "known keys here"},
        {R"({"events": [{"frame": 1}]})", "'events[0]'", "needs one of"},
        {R"({"events": [{"frame": 1, "quit": false}]})", "'events[0].quit' = false", "must be true"},
        {R"({"events": [{"frame": 1, "quit": 1}]})", "'events[0].quit' = 1", "must be true"},
        {R"({"events": [{"frame": 1, "tap": "p", "quit": true}]})", "'events[0]'", "one action per entry"},
        {R"({"events": [{"frame": 1, "scroll": 1e39}]})", "'events[0].scroll'", "float"},
        {R"({"events": [{"frame": 1, "scroll": 101}]})", "'events[0].scroll' = 101", "100 notches"},
        {R"({"events": [], "events": []})", "duplicate key 'events'", "once"},
        {R"({"events": )" + std::string(20000, '['), "key 'events[0][0][0]", "nested deeper than 64"},
    };
    for (const Case& c : cases) {
        const std::string e = error_of(c.text);
        EXPECT_CONTAINS(e, "--input-script ");
        EXPECT_CONTAINS(e, "script.json");
        EXPECT_CONTAINS(e, c.key);
        EXPECT_CONTAINS(e, c.reason);
    }
    for (const auto& [p, reason] : {std::pair{dir_ / "missing.json", "not found"}, std::pair{dir_, "is a directory"}}) {
        try {
            read_input_script(p);
            ADD_FAILURE() << p;
        } catch (const InputError& e) {
            EXPECT_CONTAINS(e.what(), "--input-script " + p.string());
            EXPECT_CONTAINS(e.what(), reason);
        }
    }
}

}  // namespace
}  // namespace tessera::view
