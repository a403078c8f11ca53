// DataPath: lookup order (scene directory, --data-dir, $TESSERA_DATA, default) and errors.
#include <cstdlib>
#include <fstream>

#include "scene/scene_test_util.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

// Three directories that each hold a file "mesh.obj" (contents = directory name), and
// a scene directory; restores $TESSERA_DATA afterwards.
class DataPathTest : public ::testing::Test {
protected:
    void SetUp() override {
        root_ = test::unique_temp_dir("tessera_data_path_test");
        fs::remove_all(root_);
        for (const char* d : {"scene", "cli", "env"}) {
            fs::create_directories(root_ / d);
            std::ofstream(root_ / d / "mesh.obj") << d;
        }
        std::ofstream(root_ / "scene" / "s.json") << "{}";
        if (const char* old = std::getenv("TESSERA_DATA")) saved_ = old;
        setenv("TESSERA_DATA", (root_ / "env").c_str(), 1);
    }
    void TearDown() override {
        if (saved_) setenv("TESSERA_DATA", saved_->c_str(), 1); else unsetenv("TESSERA_DATA");
        fs::remove_all(root_);
    }
    fs::path scene() const { return root_ / "scene" / "s.json"; }
    fs::path root_;
    std::optional<std::string> saved_;
};

TEST_F(DataPathTest, RootsInPriorityOrder) {
    const DataPath data = make_data_path(root_ / "cli");
    ASSERT_EQ(data.roots.size(), 3u);
    EXPECT_EQ(data.roots[0], root_ / "cli");
    EXPECT_EQ(data.roots[1], root_ / "env");
    EXPECT_EQ(data.roots[2], fs::path(TESSERA_DEFAULT_DATA_DIR));
}

TEST_F(DataPathTest, EmptyEnvironmentIsIgnored) {
    setenv("TESSERA_DATA", "", 1);
    const DataPath data = make_data_path(std::nullopt);
    ASSERT_EQ(data.roots.size(), 1u);
    EXPECT_EQ(data.roots[0], fs::path(TESSERA_DEFAULT_DATA_DIR));
}

TEST_F(DataPathTest, SceneDirectoryWinsThenDataDirThenEnvironment) {
    const DataPath data = make_data_path(root_ / "cli");
    EXPECT_EQ(data.resolve("mesh.obj", scene()), root_ / "scene" / "mesh.obj");
    fs::remove(root_ / "scene" / "mesh.obj");
    EXPECT_EQ(data.resolve("mesh.obj", scene()), root_ / "cli" / "mesh.obj");
    fs::remove(root_ / "cli" / "mesh.obj");
    EXPECT_EQ(data.resolve("mesh.obj", scene()), root_ / "env" / "mesh.obj");
}

TEST_F(DataPathTest, ErrorListsEveryDirectoryTried) {
    const DataPath data = make_data_path(root_ / "cli");
    try {
        data.resolve("missing.obj", scene());
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_CONTAINS(e.what(), "missing.obj");
        EXPECT_CONTAINS(e.what(), "s.json");
        for (const auto& dir : {root_ / "scene", root_ / "cli", root_ / "env",
                                fs::path(TESSERA_DEFAULT_DATA_DIR)})
            EXPECT_CONTAINS(e.what(), dir.string());
    }
}

TEST_F(DataPathTest, MissingDataDirIsAnError) {
    try {
        make_data_path(root_ / "nope");
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_CONTAINS(e.what(), "--data-dir");
        EXPECT_CONTAINS(e.what(), "nope");
    }
}

TEST_F(DataPathTest, AbsolutePathIsUsedAsIs) {
    const DataPath data = make_data_path(std::nullopt);
    EXPECT_EQ(data.resolve((root_ / "cli" / "mesh.obj").string(), scene()), root_ / "cli" / "mesh.obj");
    EXPECT_THROW(data.resolve((root_ / "cli" / "gone.obj").string(), scene()), InputError);
}

}  // namespace
}  // namespace tessera
