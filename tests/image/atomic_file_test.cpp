// CommitGroup: the outputs of a run are renamed into place together, or not at all.
#include "image/atomic_file.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "support/scratch_dir.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace tessera {
namespace {

size_t entries(const fs::path& dir) { return size_t(std::distance(fs::directory_iterator(dir), {})); }

class CommitGroupTest : public test::ScratchDirTest {};

TEST_F(CommitGroupTest, CommitReplacesAndCreatesEveryTarget) {
    std::ofstream(dir_ / "a") << "old a";
    {
        CommitGroup g;
        std::ofstream(g.add(dir_ / "a")) << "new a";
        std::ofstream(g.add(dir_ / "b")) << "new b";
        EXPECT_EQ(tessera::test::file_bytes(dir_ / "a"), "old a");  // nothing visible before commit
        EXPECT_FALSE(fs::exists(dir_ / "b"));
        g.commit();
    }
    EXPECT_EQ(tessera::test::file_bytes(dir_ / "a"), "new a");
    EXPECT_EQ(tessera::test::file_bytes(dir_ / "b"), "new b");
    EXPECT_EQ(entries(dir_), 2u);  // no temporary, no backup left
}

// A replaced file keeps its permission bits: a private image stays private (0640 did
// become the umask's 0644), a read-only one read-only; a new file gets the umask's.
TEST_F(CommitGroupTest, AReplacedFileKeepsItsPermissionBits) {
    const auto perms = [](const fs::path& p) { return fs::status(p).permissions() & fs::perms::mask; };
    using P = fs::perms;
    std::ofstream(dir_ / "private") << "old";
    fs::permissions(dir_ / "private", P::owner_read | P::owner_write | P::group_read);
    std::ofstream(dir_ / "read-only") << "old";
    fs::permissions(dir_ / "read-only", P::owner_read | P::group_read | P::others_read);
    {
        CommitGroup g;
        std::ofstream(g.add(dir_ / "private")) << "new";
        std::ofstream(g.add(dir_ / "new")) << "new";
        g.commit();
    }
    write_file_atomic(dir_ / "read-only", "new", 3);
    EXPECT_EQ(perms(dir_ / "private"), P::owner_read | P::owner_write | P::group_read);
    EXPECT_EQ(perms(dir_ / "read-only"), P::owner_read | P::group_read | P::others_read);
    EXPECT_EQ(tessera::test::file_bytes(dir_ / "read-only"), "new");
    EXPECT_TRUE((perms(dir_ / "new") & P::owner_write) == P::owner_write);
}

// A target that is a symbolic link to a file replaces that file; the link stays a link
// (a rename over it made it a plain file and left the file it pointed to as it was).
TEST_F(CommitGroupTest, ALinkToAFileReplacesTheFileItPointsTo) {
    fs::create_directory(dir_ / "real");
    std::ofstream(dir_ / "real" / "image") << "old";
    fs::create_symlink(dir_ / "real" / "image", dir_ / "link");
    {
        CommitGroup g;
        std::ofstream(g.add(dir_ / "link")) << "new";
        g.commit();
    }
    EXPECT_TRUE(fs::is_symlink(dir_ / "link"));
    EXPECT_EQ(tessera::test::file_bytes(dir_ / "real" / "image"), "new");
    write_file_atomic(dir_ / "link", "newer", 5);
    EXPECT_TRUE(fs::is_symlink(dir_ / "link"));
    EXPECT_EQ(tessera::test::file_bytes(dir_ / "real" / "image"), "newer");
    EXPECT_EQ(entries(dir_ / "real"), 1u);  // no temporary left beside the file
}

// A link to nothing yet (a relative one) gets its file made where it points, directory
// included, and stays a link (it became a plain file).
TEST_F(CommitGroupTest, ALinkToNothingYetMakesTheFileItNames) {
    fs::create_symlink("sub/final", dir_ / "dangling");
    EXPECT_EQ(output_target(dir_ / "dangling"), dir_ / "sub/final");
    write_file_atomic(dir_ / "dangling", "new", 3);
    EXPECT_TRUE(fs::is_symlink(dir_ / "dangling"));
    EXPECT_EQ(tessera::test::file_bytes(dir_ / "sub" / "final"), "new");
    EXPECT_EQ(output_target(dir_ / "plain"), dir_ / "plain");
}

TEST_F(CommitGroupTest, NoCommitLeavesEverythingAsItWas) {
    std::ofstream(dir_ / "a") << "old a";
    {
        CommitGroup g;
        std::ofstream(g.add(dir_ / "a")) << "new a";
        std::ofstream(g.add(dir_ / "b")) << "new b";
    }  // an exception before commit ends here too
    EXPECT_EQ(tessera::test::file_bytes(dir_ / "a"), "old a");
    EXPECT_EQ(entries(dir_), 1u);
}

// The third rename fails (its target is a non-empty directory): the first two targets
// are put back, the replaced one with its old bytes, the new one removed.
TEST_F(CommitGroupTest, AFailedRenameRollsBackTheOthers) {
    std::ofstream(dir_ / "a") << "old a";
    fs::create_directories(dir_ / "c" / "inside");
    CommitGroup g;
    std::ofstream(g.add(dir_ / "a")) << "new a";
    std::ofstream(g.add(dir_ / "b")) << "new b";
    std::ofstream(g.add(dir_ / "c")) << "new c";
    try {
        g.commit();
        FAIL() << "commit over a directory succeeded";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find((dir_ / "c").string()), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("rename failed"), std::string::npos) << e.what();
    }
    EXPECT_EQ(tessera::test::file_bytes(dir_ / "a"), "old a");
    EXPECT_FALSE(fs::exists(dir_ / "b"));
    EXPECT_TRUE(fs::is_directory(dir_ / "c" / "inside"));
}

TEST_F(CommitGroupTest, AddNamesTheTargetWhenNoTemporaryCanBeMade) {
    CommitGroup g;
    std::ofstream(dir_ / "file") << "a regular file, where a directory would have to be";
    try {
        g.add(dir_ / "file" / "a");
        FAIL();
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find((dir_ / "file" / "a").string()), std::string::npos) << e.what();
    }
}

// A write that fails (here as a full disk reports it) names the file asked for, not the
// hidden temporary it was filling; the group then leaves nothing behind.
TEST_F(CommitGroupTest, AFailedWriteNamesTheTargetNotTheTemporary) {
    const fs::path target = dir_ / "out.exr";
    std::string temp;
    try {
        CommitGroup g;
        g.write(target, [&temp](const fs::path& t) {
            temp = t.string();
            throw RuntimeError("cannot write '" + temp + "': No space left on device");
        });
        FAIL() << "the write's error was lost";
    } catch (const RuntimeError& e) {
        EXPECT_EQ(std::string(e.what()), "cannot write '" + target.string() + "': No space left on device");
    }
    EXPECT_NE(temp, target.string());
    EXPECT_EQ(entries(dir_), 0u);
}

// A tool that filled two of the group's temporaries and failed names both files asked
// for (a link as given, not the file it points to); an error naming no temporary, or of
// another type, keeps its type and message.
TEST_F(CommitGroupTest, NamingTargetsShowsEveryTemporaryAsItsTarget) {
    const fs::path a = dir_ / "a.png", b = dir_ / "b.png", link = dir_ / "link.png";
    fs::create_symlink("b.png", link);
    CommitGroup g;
    const fs::path ta = g.add(a), tb = g.add(link);
    EXPECT_EQ(g.shown("wrote '" + ta.string() + "', not '" + tb.string() + "'"),
              "wrote '" + a.string() + "', not '" + link.string() + "'");
    try {
        g.naming_targets([&] { throw RuntimeError("tool failed on " + tb.string() + " after " + ta.string()); });
        FAIL() << "the error was lost";
    } catch (const RuntimeError& e) {
        EXPECT_EQ(std::string(e.what()), "tool failed on " + link.string() + " after " + a.string());
    }
    struct Other : RuntimeError {
        using RuntimeError::RuntimeError;
    };
    EXPECT_THROW(g.naming_targets([] { throw Other("about nothing of the group's"); }), Other);
    EXPECT_THROW(g.naming_targets([&] { throw std::invalid_argument(ta.string()); }), std::invalid_argument);
    g.naming_targets([] {});
}

// A library's message naming the temporary twice names the file asked for twice.
TEST(WithPathShown, ReplacesEveryMentionOfTheTemporary) {
    EXPECT_EQ(with_path_shown("'d/.x.tmp.1' failed: 'd/.x.tmp.1' is full", "d/.x.tmp.1", "d/x"),
              "'d/x' failed: 'd/x' is full");
    EXPECT_EQ(with_path_shown("no mention", "d/.x.tmp.1", "d/x"), "no mention");
}

// A group that fails (destroyed before commit) takes away the directories it made, unless
// something else was written there meanwhile: an interrupted `render --frames` into a new
// directory left it behind, empty.
TEST_F(CommitGroupTest, FailedGroupRemovesTheDirectoriesItMade) {
    {
        CommitGroup g;
        std::ofstream(g.add(dir_ / "new" / "deeper" / "a")) << "A";
        std::ofstream(g.add(dir_ / "new" / "b")) << "B";
        EXPECT_TRUE(fs::is_directory(dir_ / "new" / "deeper"));
    }
    EXPECT_FALSE(fs::exists(dir_ / "new"));
    {
        CommitGroup g;
        std::ofstream(g.add(dir_ / "kept" / "a")) << "A";
        std::ofstream(dir_ / "kept" / "other") << "written by someone else";
    }
    EXPECT_TRUE(fs::exists(dir_ / "kept" / "other"));
    EXPECT_FALSE(fs::exists(dir_ / "kept" / "a"));
}

// A target's missing directory is made at its first write (the CLI checks make none, so a
// run that fails before it writes leaves nothing behind), and the commit lands there.
TEST_F(CommitGroupTest, AddMakesAMissingDirectory) {
    CommitGroup g;
    const fs::path target = dir_ / "new" / "deeper" / "a";
    std::ofstream(g.add(target)) << "A";
    EXPECT_TRUE(fs::is_directory(dir_ / "new" / "deeper"));
    g.commit();
    EXPECT_EQ(tessera::test::file_bytes(target), "A");
}

class ExistingAncestorTest : public test::ScratchDirTest {};

TEST_F(ExistingAncestorTest, IsTheNearestDirectoryThatExists) {
    fs::create_directories(dir_ / "a");
    EXPECT_EQ(existing_ancestor(dir_ / "a"), dir_ / "a");
    EXPECT_EQ(existing_ancestor(dir_ / "a" / "b" / "c"), dir_ / "a");
    EXPECT_EQ(existing_ancestor(fs::path("/")), fs::path("/"));
    // Relative: "." stands for the working directory, also past the first missing part.
    EXPECT_EQ(existing_ancestor(fs::path()), fs::path("."));
    EXPECT_EQ(existing_ancestor(fs::path("no-such-dir-for-tessera/x")), fs::path("."));
    // A file on the way is what exists there: the callers refuse it as "not a directory".
    std::ofstream(dir_ / "file") << "x";
    EXPECT_EQ(existing_ancestor(dir_ / "file" / "d"), dir_ / "file");
}

}  // namespace
}  // namespace tessera
