// terminal_safe (host/util/terminal_safe.h): the controls a terminal acts on are written out,
// everything else is left as it is; and the CLI's messages quote input text through it.
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "support/scratch_dir.h"
#include "support/shell.h"
#include "util/terminal_safe.h"

namespace tessera {
namespace {

TEST(TerminalSafe, WritesOutTheControlsATerminalActsOn) {
    EXPECT_EQ(terminal_safe("x\x1b[31mX"), "x\\x1b[31mX");            // ESC: recolours
    EXPECT_EQ(terminal_safe("\x1b]0;T\x07"), "\\x1b]0;T\\x07");          // OSC ... BEL: retitles
    EXPECT_EQ(terminal_safe("a\rb\x7f"), "a\\x0db\\x7f");                // CR overwrites; DEL
    EXPECT_EQ(terminal_safe("x\xc2\x9by"), "x\\u009by");                 // U+009B, a one-character CSI
    EXPECT_EQ(terminal_safe(std::string("a\0b", 3)), "a\\x00b");
    EXPECT_EQ(terminal_safe("\xc2"), "\xc2");                            // a lone lead byte: no C1 control
}

TEST(TerminalSafe, LeavesEverythingElse) {
    const std::string text = "line one\n\tcaf\xc3\xa9 \xc2\xa0 \xe2\x82\xac \xc2\xa9 ~ ";  // é, NBSP, €, ©
    EXPECT_EQ(terminal_safe(text), text);
    EXPECT_TRUE(is_printable_line("caf\xc3\xa9 \xe2\x82\xac"));
    EXPECT_FALSE(is_printable_line("two\nlines"));
    EXPECT_FALSE(is_printable_line("x\xc2\x85y"));  // U+0085, NEL
}

class TerminalSafeCli : public test::ScratchDirTest {};

// An OBJ line with an escape sequence: the error quotes it escaped, not raw.
TEST_F(TerminalSafeCli, ErrorsQuoteInputTextEscaped) {
    std::ofstream(dir_ / "esc.obj") << "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 \x1b[31mX\n";
    std::ofstream(dir_ / "esc.json")
        << R"({"camera": {"position": [0, 2, 3], "look_at": [0, 0, 0]}, "objects": [{"mesh": "esc.obj"}]})";
    const test::CliResult r = test::run_tessera("info " + (dir_ / "esc.json").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("'\\x1b[31mX'"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find('\x1b'), std::string::npos) << r.output;
}

}  // namespace
}  // namespace tessera
