// run_tool (host/metrics/external_tool.h): exit status and both output streams of a real
// subprocess, and a program that cannot be started; neither leaves its output files.
#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "metrics/external_tool.h"
#include "support/scratch_dir.h"

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

// The captured streams go to files in $TMPDIR; a run that ran, and one whose program was
// missing (the spawn opens them before its exec fails), both remove them.
class ExternalToolFiles : public tessera::test::ScratchDirTest {};

TEST_F(ExternalToolFiles, NoRunLeavesItsOutputFiles) {
    const char* old = std::getenv("TMPDIR");
    const std::string saved = old ? old : "";
    ::setenv("TMPDIR", dir_.c_str(), 1);
    const ToolRun ran = run_tool({"sh", "-c", "echo out; echo err >&2"});
    const ToolRun missing = run_tool({"/nonexistent/python3", "x.py"});
    old ? ::setenv("TMPDIR", saved.c_str(), 1) : ::unsetenv("TMPDIR");
    EXPECT_EQ(ran.out, "out\n");
    EXPECT_FALSE(missing.started && missing.exit_code == 0);
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir_), {}), 0);
}

TEST(ExternalTool, LastLineSkipsTrailingNewlines) {
    EXPECT_EQ(last_line("one\ntwo\r\n\n"), "two");
    EXPECT_EQ(last_line("only"), "only");
    EXPECT_EQ(last_line(""), "");
}
