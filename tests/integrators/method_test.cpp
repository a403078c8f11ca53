// The method table (integrators/method.h): every row parses and names itself, renders,
// checkpoints and resumes to the same bits (or, when temporal, is refused --resume), and
// the commands refuse the options its flags say it lacks.
#include "integrators/method.h"

#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render/checkpoint_session.h"
#include "support/render_helpers.h"
#include "support/scratch_dir.h"
#include "support/shell.h"
#include "util/error.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

TEST(MethodTable, RowsAreInMethodOrderWithUniqueNamesThatParseBack) {
    std::set<std::string> names;
    for (size_t i = 0; i < method_table().size(); ++i) {
        const MethodInfo& row = method_table()[i];
        EXPECT_EQ(static_cast<size_t>(row.method), i) << row.name;
        EXPECT_TRUE(names.insert(row.name).second) << row.name;
        EXPECT_EQ(parse_method(row.name), row.method);
        EXPECT_STREQ(method_name(row.method), row.name);
        EXPECT_EQ(&method_info(row.method), &row);
        EXPECT_NE(row.make, nullptr) << row.name;
        EXPECT_TRUE(row.igi_family || !row.adaptive) << row.name << ": AIS is igi-family";
    }
    try {
        parse_method("bogus");
        ADD_FAILURE() << "bogus parsed";
    } catch (const InputError& e) {
        for (const std::string& n : names) EXPECT_NE(std::string(e.what()).find(n), std::string::npos) << e.what();
    }
}

class MethodRows : public test::ScratchDirTest, public ::testing::WithParamInterface<Method> {};

// Every row renders a finite, lit image, and one interrupted by checkpoints resumes to the
// same bits as the uninterrupted render.
TEST_P(MethodRows, RendersAndResumesFromACheckpoint) {
    const MethodInfo& row = method_info(GetParam());
    const Scene scene = load_scene(default_scene_path(), make_data_path(std::nullopt));
    SceneBuffers buffers = make_scene_buffers(scene);
    auto backend = make_backend(BackendOptions{BackendKind::Embree, ""}, buffers, plan_effects(scene));
    RenderSettings rs;
    rs.method = row.method;
    rs.width = rs.height = 12;
    rs.spp = 3;
    rs.shadow_samples = 2;
    rs.igi.paths_per_set = 4;
    rs.checkpoint_interval_s = 1e-9;  // after every pass but the last
    if (row.prepare) prepare_sequence(rs, scene);
    CheckpointOptions ck{dir_ / "ckpt", BackendKind::Embree, false};
    const Image whole = render_frame(*backend, scene, buffers, rs, nullptr, {}, &ck);
    double sum = 0;
    for (const char* c : {"R", "G", "B"})
        for (float v : whole.find(c)->data) {
            ASSERT_TRUE(std::isfinite(v)) << row.name;
            sum += v;
        }
    EXPECT_GT(sum, 0.0) << row.name;
    ASSERT_TRUE(fs::exists(ck.path)) << row.name;
    if (row.temporal) return;  // its state is not in the checkpoint: the CLI refuses --resume (below)
    ck.resume = true;
    RenderStats stats;
    const Image resumed = render_frame(*backend, scene, buffers, rs, &stats, {}, &ck);
    EXPECT_EQ(stats.passes, 1u) << row.name;
    for (const char* c : {"R", "G", "B"}) EXPECT_EQ(whole.find(c)->data, resumed.find(c)->data) << row.name << " " << c;
}

// What a row's flags say it lacks, the command refuses before any work, naming the option.
class MethodRowsCli : public MethodRows {};  // runs the executable: the cli tier

TEST_P(MethodRowsCli, CommandRefusesWhatTheRowLacks) {
    const MethodInfo& row = method_info(GetParam());
    const std::string render = std::string("render --backend embree --width 4 --height 4 --spp 1 --method ") +
                               row.name + " --out " + (dir_ / "out.exr").string() + " ";
    auto refused = [&](const std::string& args, const std::string& message) {
        const test::CliResult r = test::run_tessera(render + args);
        EXPECT_EQ(r.exit_code, 2) << row.name << " " << args << ": " << r.output;
        EXPECT_NE(r.output.find(message), std::string::npos) << row.name << " " << args << ": " << r.output;
        EXPECT_FALSE(fs::exists(dir_ / "out.exr"));
    };
    if (!row.igi_family) refused("--components ss", "has no components");
    if (row.igi_family && !row.adaptive) refused("--components ss,edge", "edge samples are an AIS component");
    if (row.temporal) refused("--resume", "cannot be combined with --resume");
    refused("--spp 0", "--spp 0");  // and every row refuses an out-of-range option
}

std::vector<Method> every_row() {  // a new row is tested without an edit here
    std::vector<Method> rows;
    for (const MethodInfo& row : method_table()) rows.push_back(row.method);
    return rows;
}
const auto kRows = ::testing::ValuesIn(every_row());
std::string row_name(const ::testing::TestParamInfo<Method>& info) {
    std::string n = method_name(info.param);
    for (char& c : n)
        if (c == '-') c = '_';
    return n;
}
INSTANTIATE_TEST_SUITE_P(Rows, MethodRows, kRows, row_name);
INSTANTIATE_TEST_SUITE_P(Rows, MethodRowsCli, kRows, row_name);

}  // namespace
}  // namespace tessera
