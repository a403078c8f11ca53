// The input contract of the command line (docs/input-limits.md): every bad option value and every
// output that cannot be written is rejected before any work, with one message naming
// the option (or file) and the value, exit status 2 (bad input) or 1 (the environment),
// and no file created or changed: each case first writes sentinel files where the run
// would write, and checks their bytes and the directory listing afterwards.
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "support/shell.h"

#include "support/scratch_dir.h"

namespace fs = std::filesystem;

namespace {

using tessera::test::CliResult;
using tessera::test::run_shell;
using tessera::test::run_tessera;

// Every file under `dir` with its bytes (directories as "<dir>", symbolic links as
// "<link>": some lead nowhere).
std::map<std::string, std::string> snapshot(const fs::path& dir) {
    std::map<std::string, std::string> files;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        files[e.path().lexically_relative(dir).string()] = e.is_symlink()     ? "<link>"
                                                      : e.is_directory() ? "<dir>"
                                                                         : tessera::test::file_bytes(e.path());
    return files;
}

const std::string kData = TESSERA_TEST_DATA;
const std::string kScenes = std::string(TESSERA_SOURCE_DIR) + "/scenes";

struct Case {
    std::string args;     // after `tessera`; $D is replaced by the scratch directory
    std::string message;  // the error message (after "tessera: error: "), $D replaced
    int exit_code = 2;
    std::function<void(const fs::path& dir)> setup = {};  // besides the sentinels
};

class ContractCli : public tessera::test::ScratchDirTest {
protected:
    std::string expand(std::string s) const {
        for (size_t at; (at = s.find("$D")) != std::string::npos;) s.replace(at, 2, dir_.string());
        return s;
    }

    void expect_rejected(const Case& c) {
        SCOPED_TRACE(c.args);
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        // Sentinels where the run writes: they must keep their bytes.
        for (const char* name : {"img.exr", "img.png", "img.ckpt", "stats.json", "anim.0000.exr", "anim.0000.png"})
            std::ofstream(dir_ / name) << "SENTINEL " << name;
        if (c.setup) c.setup(dir_);
        const auto before = snapshot(dir_);
        const CliResult r = run_tessera(expand(c.args));
        EXPECT_EQ(r.exit_code, c.exit_code) << r.output;
        // Bad input: the whole line; the environment (exit 1): the OS reason follows.
        const std::string line = "tessera: error: " + expand(c.message) + (c.exit_code == 2 ? "\n" : ": ");
        EXPECT_NE(r.output.find(line), std::string::npos) << r.output;
        // The line before the first pass ("tessera: <scene>, N triangles, ...") never came.
        EXPECT_EQ(r.output.find(" triangles"), std::string::npos) << "rendering started:\n" << r.output;
        EXPECT_EQ(snapshot(dir_), before) << "a file was created or changed";
    }
};

const std::string kRender = "render " + kData + "/light.json --backend embree --spp 1 ";

// tests/data's textured scene (JSON, OBJ, MTL, PNG) copied into the scratch directory.
void copy_textured_scene(const fs::path& d) {
    for (const char* f : {"textured.json", "textured.obj", "textured.mtl", "checker.png"})
        fs::copy_file(fs::path(kData) / f, d / f, fs::copy_options::overwrite_existing);
}
const std::string kOut = " --out $D/img.exr";

// Option values out of range, not finite, empty or meaningless here.
TEST_F(ContractCli, BadOptionValuesAreRejectedBeforeAnyWork) {
    const std::vector<Case> cases = {
        {kRender + "--width 0" + kOut, "--width 0: must be in 1..16384 (leave the option out for the scene camera's)"},
        {kRender + "--height 0" + kOut, "--height 0: must be in 1..16384 (leave the option out for the scene camera's)"},
        {kRender + "--width -5" + kOut, "--width -5: must be in 1..16384"},
        {kRender.substr(0, kRender.size() - 8) + "--spp -1" + kOut, "--spp -1: must be in 1..1000000"},
        {kRender.substr(0, kRender.size() - 8) + "--spp ''" + kOut, "--spp '': must be an integer in 1..1000000"},
        {kRender.substr(0, kRender.size() - 8) + "--spp 2.5" + kOut, "--spp 2.5: must be an integer in 1..1000000"},
        {kRender + "--seed -1" + kOut, "--seed -1: must be in 0..4294967295"},
        // A pass cannot be interrupted: 2^32 steps took 25 minutes for one pixel.
        {kRender + "--method igi --march-steps 65537" + kOut, "--march-steps 65537: must be in 0..65536"},
        {kRender + "--seed 4294967296" + kOut, "--seed 4294967296: must be in 0..4294967295"},
        {kRender + "--clamp inf" + kOut, "--clamp inf: must be a finite number in [0, 1]"},
        {kRender + "--ic-error nan" + kOut, "--ic-error nan: must be a finite number in [0.001, 2]"},
        {kRender + "--checkpoint-interval -1" + kOut, "--checkpoint-interval -1: must be >= 0"},
        {kRender + "--exposure nan" + kOut, "--exposure nan: must be a finite number >= -64 and <= 64"},
        {kRender + "--exposure inf" + kOut, "--exposure inf: must be a finite number >= -64 and <= 64"},
        {kRender + "--exposure ''" + kOut, "--exposure '': must be a finite number >= -64 and <= 64"},
        // 2^1e39 overflows the preview's float scale (it failed at the PNG, after the render).
        {kRender + "--exposure 1e39" + kOut, "--exposure 1e39: must be a finite number >= -64 and <= 64"},
        {kRender + "--exposure -64.5" + kOut, "--exposure -64.5: must be a finite number >= -64 and <= 64"},
        // A parse error is bad input: exit 2, not CLI11's own code (109).
        {kRender + "--bogus" + kOut, "The following argument was not expected: --bogus (see --help)"},
        // A value left out: CLI11 took "--out" as the file and the path after it as the scene.
        {kRender + "--stats-json" + kOut, "--stats-json: needs a value (the next word, --out, is an option)"},
        {"compare $D/img.exr $D/img.exr --map --no-flip", "--map: needs a value (the next word, --no-flip, is an option)"},
        // Given more than once (kRender has one): CLI11 said "--spp: At Most 1 required but
        // received 3".
        {kRender + "--spp 2 --spp 3" + kOut, "--spp: given 3 times; give it once (see --help)"},
        {kRender + "--out ''", "--out '': must not be empty"},
        {kRender + "--stats-json ''" + kOut, "--stats-json '': must not be empty"},
        {kRender + "--data-dir ''" + kOut, "--data-dir '': must not be empty"},
        {kRender + "--frames ''" + kOut, "--frames '': must not be empty"},
        {kRender + "--method ''" + kOut, "--method '': must not be empty"},
        {kRender + "--components ''" + kOut, "--components '': must not be empty"},
        {kRender + "--device ''" + kOut, "--device '': must not be empty"},
        {"render '' --backend embree" + kOut, "scene '': must not be empty"},
        {kRender + "--device 0" + kOut, "--device 0: only --backend opencl uses a device (this run has --backend embree)"},
        {kRender + "--data-dir $D/nowhere" + kOut, "--data-dir $D/nowhere: no such directory"},
        {kRender + "--data-dir $D/img.exr" + kOut, "--data-dir $D/img.exr: not a directory"},
        {"render " + kScenes + "/cornell-box-fog.json --backend embree --spp 1 --method igi --march-steps 0" + kOut,
         "--march-steps 0: scene " + kScenes + "/cornell-box-fog.json has a medium, whose light and transmittance "
         "--method igi computes by a ray march; give at least 1 step"},
        {"info ''", "scene '': must not be empty"},
        {"rendr " + kData + "/light.json",
         "unknown command 'rendr'; the commands are render, devices, info, compare, options, view (see --help)"},
        {"info " + kData + "/light.json --data-dir $D/nowhere", "--data-dir $D/nowhere: no such directory"},
        {"compare $D/img.exr $D/img.exr --exposure nan", "--exposure nan: must be a finite number >= -64 and <= 64"},
        {"compare $D/img.exr $D/img.exr --exposure 1e39", "--exposure 1e39: must be a finite number >= -64 and <= 64"},
        {"compare $D/img.exr $D/img.exr --map ''", "--map '': must not be empty"},
    };
    for (const Case& c : cases) expect_rejected(c);
}

// Outputs that cannot be written: found before the first ray, nothing written.
TEST_F(ContractCli, UnwritableOutputsAreRejectedBeforeAnyWork) {
    auto mkdir = [](const char* name) {
        return [=](const fs::path& d) {
            fs::remove(d / name);  // a sentinel file may be there
            fs::create_directory(d / name);
        };
    };
    // The scratch file system's name limit (255 on most; eCryptfs 143).
    const long name_max = ::pathconf(dir_.c_str(), _PC_NAME_MAX) > 0 ? ::pathconf(dir_.c_str(), _PC_NAME_MAX) : 255;
    const std::string long_file(size_t(name_max - 23 - 4), 'a'), long_dir(size_t(name_max + 45), 'b');
    const std::string anim = "render " + kScenes + "/cornell-box-animated.json --backend embree --spp 1 "
                             "--width 8 --height 8 --frames 0:2 --out $D/anim.exr";
    const std::vector<Case> cases = {
        {kRender + kOut, "--out's PNG preview $D/img.png: is a directory", 2, mkdir("img.png")},
        {kRender + "--out $D/dir.exr", "--out $D/dir.exr: is a directory", 2, mkdir("dir.exr")},
        {kRender + kOut, "--out's checkpoint $D/img.ckpt: is a directory", 2, mkdir("img.ckpt")},
        {kRender + "--out $D/stats.json/img.exr", "--out $D/stats.json/img.exr: $D/stats.json is not a directory"},
        {kRender + kOut + " --stats-json $D/sub", "--stats-json $D/sub: is a directory", 2, mkdir("sub")},
        {kRender + kOut + " --stats-json $D/img.png", "--stats-json $D/img.png: is also --out's PNG preview"},
        {kRender + kOut + " --stats-json /proc/tessera-stats.json", "--stats-json /proc/tessera-stats.json: cannot write "
                                                                    "in /proc", 1},
        {kRender + kOut + " --stats-json /proc/tessera/stats.json",
         "--stats-json /proc/tessera/stats.json: cannot create the directory /proc/tessera", 1},
        {kRender + kOut + " --stats-json /dev/null", "--stats-json /dev/null: not a regular file"},
        {kRender + "--out $D/", "--out $D/: ends in '/'; name the file, e.g. $D/image.exr"},
        {kRender + "--out $D/sub", "--out $D/sub: is a directory; name the file, e.g. $D/sub/image.exr", 2,
         mkdir("sub")},
        {kRender + "--out $D/img.EXR", "--out $D/img.EXR: must end in .exr (lower case)"},
        {kRender + "--out $D/.exr", "--out $D/.exr: needs a file name before .exr"},
        {anim, "frame 1 of --out $D/anim.0001.exr: is a directory", 2, mkdir("anim.0001.exr")},
        {anim, "the PNG preview of frame 2 $D/anim.0002.png: is a directory", 2, mkdir("anim.0002.png")},
        {"compare " + kData + "/x.exr " + kData + "/y.exr --map $D/sub", "--map $D/sub: is a directory", 2, mkdir("sub")},
        // The files the scene reads are inputs too: a texture, an OBJ, an MTL.
        {"render $D/textured.json --backend embree --spp 1 --out $D/checker.exr",
         "--out's PNG preview $D/checker.png: would replace an input of this run, $D/checker.png", 2,
         copy_textured_scene},
        {"render $D/textured.json --backend embree --spp 1" + kOut + " --stats-json $D/textured.obj",
         "--stats-json $D/textured.obj: would replace an input of this run, $D/textured.obj", 2, copy_textured_scene},
        {"render $D/textured.json --backend embree --spp 1" + kOut + " --stats-json $D/textured.mtl",
         "--stats-json $D/textured.mtl: would replace an input of this run, $D/textured.mtl", 2, copy_textured_scene},
        {"render $D/textured.json --backend embree --spp 1" + kOut + " --stats-json $D/textured.json",
         "--stats-json $D/textured.json: is the scene file", 2,
         copy_textured_scene},
        // A directory that is a link to nothing: found now, not when the image is written.
        {kRender + "--out $D/gone/img.exr", "--out $D/gone/img.exr: $D/gone is a symbolic link to nothing (a missing "
                                            "target or a loop)", 2,
         [](const fs::path& d) { fs::create_directory_symlink(d / "nowhere", d / "gone"); }},
        {kRender + "--out $D/loop/sub/img.exr", "--out $D/loop/sub/img.exr: $D/loop is a symbolic link to nothing (a "
                                                "missing target or a loop)", 2,
         [](const fs::path& d) { fs::create_directory_symlink(d / "loop", d / "loop"); }},
        // An output that is a link to a file not there yet: written through only into a
        // directory that exists (no directory is made where a link points).
        {kRender + "--out $D/d.exr", "--out $D/d.exr: is a symbolic link to $D/nowhere/x.exr, whose directory "
                                     "$D/nowhere does not exist", 2,
         [](const fs::path& d) { fs::create_symlink(d / "nowhere" / "x.exr", d / "d.exr"); }},
        {kRender + "--out $D/self.exr", "--out $D/self.exr: is a symbolic link in a loop", 2,
         [](const fs::path& d) { fs::create_symlink(d / "self.exr", d / "self.exr"); }},
        // Names the writer could not make: the EXR's temporaries add 24 bytes, so a legal
        // name of 232 bytes (NAME_MAX 255) failed after the render.
        {kRender + "--out $D/" + long_file + ".exr",
         "--out $D/" + long_file + ".exr: the file name is " + std::to_string(name_max - 23) + " bytes; at most " +
             std::to_string(name_max - 24) + " here (it is written through temporaries whose names are up to 24 "
             "bytes longer)"},
        {kRender + "--out $D/" + long_dir + "/img.exr",
         "--out $D/" + long_dir + "/img.exr: the directory name bbbbbbbbbbbbbbbb... is " +
             std::to_string(long_dir.size()) + " bytes; at most " + std::to_string(name_max) + " here"},
        // Failures found after the outputs are checked make no directory for them (the
        // writers make it at their first write): a missing checkpoint, an unknown device.
        {kRender + "--resume --out $D/new/img.exr",
         "--resume: no checkpoint $D/new/img.ckpt (it is written beside --out when a render is interrupted)"},
    };
    for (const Case& c : cases) expect_rejected(c);
}

// Failures of the OpenCL set-up come after the outputs are checked: they too leave no
// directory behind (the writers make it at their first write): an unknown device, a
// kernel build failure.
TEST_F(ContractCli, OpenClSetUpFailuresMakeNoOutputDirectory) {
    const std::string render = "render " + kData + "/light.json --backend opencl --spp 1 --width 8 --height 8 ";
    const fs::path out = dir_ / "new" / "img.exr";
    for (const auto& [args, env, message] :
         {std::tuple{std::string("--device no-such-device"), std::string(), std::string("--device no-such-device")},
          std::tuple{std::string(), std::string("TESSERA_CL_OPTIONS=-cl-no-such-option"), std::string("-cl-no-such-option")}}) {
        SCOPED_TRACE(args + env);
        const CliResult r = run_tessera(render + args + " --out " + out.string(), env);
        EXPECT_EQ(r.exit_code, 1) << r.output;
        EXPECT_NE(r.output.find("tessera: error: "), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(dir_ / "new")) << r.output;
    }
}

// The viewer's options and files, --components and compare's maps: rejected with the
// option (or file and entry) and the value, before the first frame, nothing written.
TEST_F(ContractCli, ViewComponentsAndCompareSurfacesAreRejectedBeforeAnyWork) {
    const std::string cam = R"({"position": [0.278, 0.273, -0.8], "look_at": [0.278, 0.273, 0], "up": [0, 1, 0], "vfov": 39})";
    auto files = [cam](const fs::path& d) {
        std::ofstream(d / "s.json") << R"({"events": [{"frame": 4, "quit": true}]})";
        std::ofstream(d / "path.json") << "{\"cameras\": [" + cam + ", " + cam +
                                              R"(, {"position": [0, 0, 0], "look_at": [0, 1, 0], "up": [0, 1, 0], "vfov": 39}]})";
        fs::create_directories(d / "frames" / "frame.0002.exr");
    };
    const std::string view = "view --backend embree --headless --width 8 --height 8 --input-script $D/s.json ";
    const std::vector<Case> cases = {
        {view + "--speed 0", "--speed 0: must be a finite number > 0 and <= 1e+12", 2, files},
        {view + "--speed inf", "--speed inf: must be a finite number > 0 and <= 1e+12", 2, files},
        {view + "--speed nan", "--speed nan: must be a finite number > 0 and <= 1e+12", 2, files},
        {view + "--screenshot-window-frame -1", "--screenshot-window-frame -1: must be an integer in 0..999999", 2, files},
        // Orphan options: read only with another one (they were ignored without a word).
        {view + "--screenshot-window-frame 5",
         "--screenshot-window-frame 5: is read only with --screenshot-window (the frame after which it captures the "
         "window)", 2, files},
        {"view --backend embree --headless --width 8 --height 8 --input-script $D/e.json",
         "--input-script $D/e.json: key 'events' = []: an input script needs at least one event", 2,
         [](const fs::path& d) { std::ofstream(d / "e.json") << R"({"events": []})"; }},
        // As render: PM alone on a scene without a medium (the default Cornell box) is black.
        {view + "--components pm", "--components pm: on scene " + std::string(TESSERA_SCENES_DIR) +
                                       "/cornell-box.json, PM computes nothing (medium: none declared); add ss or id",
         2, files},
        // The M key reaches the igi family from any --method, so the viewer checks them whatever it starts with.
        {view + "--method direct --components pm", "--components pm: on scene " + std::string(TESSERA_SCENES_DIR) +
                                                       "/cornell-box.json, PM computes nothing (medium: none "
                                                       "declared); add ss or id",
         2, files},
        {view + "--target-fps 0", "--target-fps 0: must be a finite number > 0 and <= 1000", 2, files},
        {view + "--target-fps nan", "--target-fps nan: must be a finite number > 0 and <= 1000", 2, files},
        {view + "--target-fps inf", "--target-fps inf: must be a finite number > 0 and <= 1000", 2, files},
        {view + "--min-scale 0", "--min-scale 0: must be a finite number > 0 and <= 1", 2, files},
        {view + "--min-scale 1.5", "--min-scale 1.5: must be a finite number > 0 and <= 1", 2, files},
        {view + "--min-scale 0.5", "--min-scale 0.5: is read only with --target-fps (the floor of its resolution scale)",
         2, files},
        {view + "--pareto $D/none.csv", "--pareto $D/none.csv: is read only with --target-fps (the frame budget it feeds)",
         2, files},
        {view + "--frame-images $D/frames",
         "--frame-images (frame 2) $D/frames/frame.0002.exr: is a directory", 2, files},
        {"view --backend embree --headless --width 8 --height 8 --camera-path $D/path.json --frame-images $D/out",
         "--camera-path $D/path.json: key 'cameras[2]' = {\"look_at\":[0,1,0],\"position\":[0,0,0],\"up\":[0,1,0],\"vfov\"...: "
         "up is zero or parallel to the view direction",
         2, files},
        {kRender + "--components ss,ss" + kOut, "--components ss,ss: 'ss' is listed twice"},
        {kRender + "--components ss,id,pm,ss" + kOut, "--components ss,id,pm,ss: 'ss' is listed twice"},
        {kRender + "--components ss," + kOut,
         "--components ss,: expected a comma-separated list of ss, id, pm, edge (an entry is empty)"},
        {kRender + "--method igi --components ss,edge" + kOut,
         "--components ss,edge: edge samples are an AIS component (--method ais or ais-max), not --method igi"},
        {kRender + "--method ais --ais-edge-samples 16" + kOut, "--ais-edge-samples 16: must be in 1..15"},
        // Only components a scene without a medium skips: the image would be black.
        {kRender + "--method igi --components pm" + kOut,
         "--components pm: on scene " + kData + "/light.json, PM computes nothing (medium: none declared); add ss or id"},
        {kRender + "--method ais --components edge,pm" + kOut,
         "--components edge,pm: on scene " + kData + "/light.json, PM computes nothing (medium: none declared), edge samples "
         "only refine the other components' pixels; add ss or id"},
        // With a medium, edge samples alone still refine nothing.
        {"render " + std::string(TESSERA_SCENES_DIR) + "/cornell-box-fog.json --backend embree --spp 1 --method ais "
         "--components edge" + kOut,
         "--components edge: on scene " + std::string(TESSERA_SCENES_DIR) + "/cornell-box-fog.json, edge samples only "
         "refine the other components' pixels; add ss, id or pm"},
        {kRender + "--method pt --components ss" + kOut,
         "--components ss: --method pt has no components (they select what igi, ais, ais-max, ic and tic compute)"},
        {"compare $D/img.exr $D/img.exr --map $D/m.exr", "--map $D/m.exr: the map is written as PNG; name it .png"},
        {"compare $D/img.exr $D/img.exr --flip-map $D/f.exr", "--flip-map $D/f.exr: the map is written as PNG; name it .png"},
        {view + "--times $D/s.json", "--times $D/s.json: would replace an input of this run, $D/s.json", 2, files},
        // Every frame the script's run writes is checked, not only the first.
        {view + "--frame-images $D/fi --times $D/fi/frame.0003.exr",
         "--frame-images (frame 3) $D/fi/frame.0003.exr: is also --times", 2, files},
        {view + "--screenshot $D/shot.exr --times $D/shot.0000.png",
         "--times $D/shot.0000.png: is also the PNG beside --screenshot", 2, files},
        {view + "--screenshot-window $D/w.png",
         "--screenshot-window $D/w.png: a headless run has no window to capture (--frame-images writes its frames)", 2,
         files},
    };
    for (const Case& c : cases) expect_rejected(c);
}

// A valid run replaces every output, leaves no temporary file and no checkpoint.
TEST_F(ContractCli, AValidRunWritesEveryOutputAndNothingElse) {
    for (const char* name : {"img.exr", "img.png", "stats.json"}) std::ofstream(dir_ / name) << "OLD";
    const CliResult r = run_tessera(kRender + "--width 8 --height 8" + expand(kOut) + " --stats-json " +
                                    (dir_ / "stats.json").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    std::vector<std::string> names;
    for (const auto& [name, bytes] : snapshot(dir_)) {
        names.push_back(name);
        EXPECT_NE(bytes, "OLD") << name << " was not replaced";
    }
    EXPECT_EQ(names, (std::vector<std::string>{"img.exr", "img.png", "stats.json"}));
    EXPECT_NE(tessera::test::file_bytes(dir_ / "stats.json").find("\"median_pass_seconds\""), std::string::npos);
}

}  // namespace
