// run_tool (host/metrics/external_tool.h): exit status and both output streams of a real
// subprocess, and a program that cannot be started.
#include <gtest/gtest.h>

#include "metrics/external_tool.h"

using namespace tessera::metrics;

TEST(ExternalTool, CapturesExitStatusAndBothStreams) {
    const ToolRun r = run_tool({"sh", "-c", "printf 'a b\\n{\"x\": 1}\\n'; printf 'first\\nlast words\\n' >&2; exit 3"});
    ASSERT_TRUE(r.started) << r.spawn_error;
    EXPECT_EQ(r.exit_code, 3);
    EXPECT_EQ(r.out, "a b\n{\"x\": 1}\n");
    EXPECT_EQ(r.err, "first\nlast words\n");
    EXPECT_EQ(last_line(r.err), "last words");
}

TEST(ExternalTool, ArgumentsPassVerbatimWithoutAShell) {
    // A path with a space and a quote reaches the program as one argument.
    const ToolRun r = run_tool({"sh", "-c", "printf '%s|' \"$@\"", "sh", "a b", "it's", "$HOME"});
    ASSERT_TRUE(r.started);
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(r.out, "a b|it's|$HOME|");
}

TEST(ExternalTool, MissingProgramIsReportedNotThrown) {
    const ToolRun r = run_tool({"/nonexistent/python3", "x.py"});
    // glibc's posix_spawnp reports the failed exec (ENOENT); another libc may exit with 127.
    EXPECT_TRUE(!r.started || r.exit_code == 127) << r.exit_code;
    if (!r.started) {
        EXPECT_NE(r.spawn_error.find("No such file"), std::string::npos) << r.spawn_error;
    }
}

TEST(ExternalTool, LastLineSkipsTrailingNewlines) {
    EXPECT_EQ(last_line("one\ntwo\r\n\n"), "two");
    EXPECT_EQ(last_line("only"), "only");
    EXPECT_EQ(last_line(""), "");
}
