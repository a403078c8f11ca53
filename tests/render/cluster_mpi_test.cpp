// Distributed renders under `mpirun --oversubscribe` on this machine (render/cluster_mpi.cpp,
// render/pass_exchange.cpp, docs/distributed.md), end to end through the tessera binary.
// Built and registered only when CMake found MPI and mpirun (tests/CMakeLists.txt).
// - pt and direct on the Cornell box and its fog version: the EXR of a 2-rank job has the
//   very bytes of a one-process render with the same --spp and --seed (and of a 1-rank job);
// - a 2-rank job interrupted by SIGINT leaves a checkpoint that a 3-rank --resume finishes
//   to the bytes of the uninterrupted one-process render;
// - igi, ais and ic (without --aov) likewise, with 3 ranks;
// - a rank that cannot open a scene data file ends the job with one message naming that
//   rank and the file, a non-zero status and no output file; tic and igi-family AOVs are
//   refused with one message.
// OpenMPI refuses root unless told otherwise (CI runs as root), hence the environment.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/scratch_dir.h"
#include "support/shell.h"

namespace fs = std::filesystem;
using tessera::test::file_bytes;
using tessera::test::run_shell;

namespace {

const std::string kMpirun = std::string("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 ") + TESSERA_MPIRUN +
                            " --oversubscribe";

std::string scene(const std::string& name) { return std::string(TESSERA_SCENES_DIR) + "/" + name; }

// Number of non-overlapping occurrences of `what` in `text`.
int count(const std::string& text, const std::string& what) {
    int n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
    return n;
}

// The process among `parent`'s children whose environment says it is MPI rank `rank`.
pid_t child_of_rank(pid_t parent, int rank) {
    const std::string want = "OMPI_COMM_WORLD_RANK=" + std::to_string(rank);
    for (const auto& entry : fs::directory_iterator("/proc")) {
        const std::string name = entry.path().filename();
        if (name.find_first_not_of("0123456789") != std::string::npos) continue;
        std::ifstream stat(entry.path() / "stat");
        std::string pid, comm, state;
        pid_t ppid = 0;
        if (!(stat >> pid >> comm >> state >> ppid) || ppid != parent) continue;
        const std::string env = file_bytes(entry.path() / "environ");
        for (size_t at = 0; at < env.size();) {
            const size_t end = env.find('\0', at);
            if (env.compare(at, end - at, want) == 0) return pid_t(std::stoi(name));
            if (end == std::string::npos) break;
            at = end + 1;
        }
    }
    return -1;
}

// Runs `mpirun --oversubscribe -n ranks tessera args` (stdout and stderr in one pipe); once
// `interrupt_on` appears in the output, sends SIGINT to rank 0 (as a signal to one rank of a
// real job; rank 0 then saves the checkpoint and stops the other ranks).
tessera::test::CliResult run_mpi_interrupted(int ranks, const std::vector<std::string>& args,
                                             const std::string& interrupt_on) {
    std::vector<std::string> words{"/usr/bin/env", "OMPI_ALLOW_RUN_AS_ROOT=1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1",
                                   TESSERA_MPIRUN, "--oversubscribe", "-n", std::to_string(ranks), TESSERA_EXE};
    words.insert(words.end(), args.begin(), args.end());
    bool sent = false;
    return tessera::test::run_watched(words, false, [&](pid_t pid, const std::string& out) {
        if (sent || out.find(interrupt_on) == std::string::npos) return;
        const pid_t rank0 = child_of_rank(pid, 0);  // env execs mpirun in this same process
        if (rank0 > 0) ::kill(rank0, SIGINT);
        sent = true;
    });
}

class DistributedCli : public tessera::test::ScratchDirTest {
protected:
    // Renders `scene_file` with `args` alone (ranks 0) or under mpirun; returns the EXR bytes.
    std::string render(int ranks, const std::string& scene_file, const std::string& args, const std::string& name) {
        const fs::path out = dir_ / (name + ".exr");
        const std::string cmd = (ranks == 0 ? std::string() : kMpirun + " -n " + std::to_string(ranks) + " ") +
                                TESSERA_EXE + " render " + scene_file + " " + args + " --out " + out.string();
        const auto r = run_shell(cmd);
        EXPECT_EQ(r.exit_code, 0) << cmd << "\n" << r.output;
        return file_bytes(out);
    }
};

TEST_F(DistributedCli, TwoRanksGiveTheBitsOfOneProcess) {
    const std::string base = "--backend embree --width 40 --height 32 --spp 7";
    for (const std::string s : {"cornell-box.json", "cornell-box-fog.json"})
        for (const std::string method : {"pt", "direct"}) {
            SCOPED_TRACE(s + " " + method);
            const std::string args = base + " --seed 3 --method " + method;
            const std::string alone = render(0, scene(s), args, "alone");
            ASSERT_GT(alone.size(), 1000u);
            EXPECT_TRUE(render(2, scene(s), args, "two") == alone);
        }
    // The comparison sees a change of one pass: another seed gives other bytes.
    EXPECT_FALSE(render(2, scene("cornell-box.json"), base + " --method pt --seed 4", "seed4") ==
                 render(0, scene("cornell-box.json"), base + " --method pt --seed 3", "seed3"));
}

TEST_F(DistributedCli, IgiFamilyWithoutAovsGivesTheBitsOfOneProcess) {
    // Their passes depend only on the seed, the pixel and the pass index too (VPLs, AIS
    // refinement and ic's cache are rebuilt per pass).
    const std::string base = "--backend embree --width 32 --height 24 --spp 4";
    for (const std::string method : {"igi", "ais", "ic"}) {
        SCOPED_TRACE(method);
        const std::string args = base + " --method " + method;
        EXPECT_TRUE(render(3, scene("cornell-box-fog.json"), args, "three") ==
                    render(0, scene("cornell-box-fog.json"), args, "alone"));
    }
}

// --stats-json says how many ranks shared the passes, so timings of distributed and
// single-process runs are not mistaken for each other.
TEST_F(DistributedCli, StatsJsonRecordsTheRanks) {
    for (const int ranks : {0, 2}) {
        const fs::path stats = dir_ / ("stats" + std::to_string(ranks) + ".json");
        render(ranks, scene("cornell-box.json"),
               "--backend embree --width 16 --height 16 --spp 4 --method pt --stats-json " + stats.string(), "s");
        std::ifstream in(stats);
        ASSERT_TRUE(in) << stats;
        EXPECT_EQ(nlohmann::json::parse(in)["mpi_ranks"].get<int>(), ranks == 0 ? 1 : ranks);
    }
}

TEST_F(DistributedCli, OneRankUnderMpirunGivesTheBitsOfOneProcess) {
    const std::string args = "--backend embree --width 40 --height 32 --spp 5 --method pt";
    EXPECT_TRUE(render(1, scene("cornell-box-fog.json"), args, "one") ==
                render(0, scene("cornell-box-fog.json"), args, "alone"));
}

TEST_F(DistributedCli, InterruptedTwoRankJobResumedWithThreeRanksGivesTheSameBits) {
    // ~0.1 s per pass on two cores (as tests/cli/checkpoint_cli_test.cpp): SIGINT lands mid-render.
    const std::vector<std::string> args{"render", scene("cornell-box.json"), "--backend", "embree", "--method",
                                        "direct", "--spp", "40", "--width", "96", "--height", "96",
                                        "--shadow-samples", "48", "--out", (dir_ / "img.exr").string()};
    const tessera::test::CliResult first = run_mpi_interrupted(2, args, "/40 spp");
    EXPECT_NE(first.exit_code, 0) << first.output;
    EXPECT_EQ(count(first.output, "checkpoint saved to"), 1) << first.output;
    ASSERT_TRUE(fs::exists(dir_ / "img.ckpt")) << first.output;
    EXPECT_FALSE(fs::exists(dir_ / "img.exr"));

    std::string resume = kMpirun + " -n 3 " + TESSERA_EXE;
    for (const auto& a : args) resume += " " + a;
    const auto second = run_shell(resume + " --resume");
    ASSERT_EQ(second.exit_code, 0) << second.output;
    EXPECT_NE(second.output.find("from the checkpoint"), std::string::npos) << second.output;
    EXPECT_FALSE(fs::exists(dir_ / "img.ckpt"));

    std::string alone = TESSERA_EXE;
    for (const auto& a : args) alone += " " + (a == (dir_ / "img.exr").string() ? (dir_ / "alone.exr").string() : a);
    ASSERT_EQ(run_shell(alone).exit_code, 0);
    EXPECT_TRUE(file_bytes(dir_ / "img.exr") == file_bytes(dir_ / "alone.exr"));
}

TEST_F(DistributedCli, RankMissingADataFileStopsTheJobWithOneMessage) {
    // Rank 0 has the box's scene and mesh; rank 1 (as on a machine without the data) only the scene.
    for (const auto* d : {"a", "b"}) {
        fs::create_directories(dir_ / d);
        fs::copy_file(scene("cornell-box.json"), dir_ / d / "box.json");
    }
    fs::copy_file(scene("cornell-box.obj"), dir_ / "a" / "cornell-box.obj");
    fs::copy_file(scene("cornell-box.mtl"), dir_ / "a" / "cornell-box.mtl");
    const std::string args = " --backend embree --width 16 --height 16 --spp 4 --out " + (dir_ / "img.exr").string();
    const auto r = run_shell(kMpirun + " -n 1 " + TESSERA_EXE + " render " + (dir_ / "a" / "box.json").string() +
                             args + " : -n 1 " + TESSERA_EXE + " render " + (dir_ / "b" / "box.json").string() + args);
    EXPECT_NE(r.exit_code, 0) << r.output;
    EXPECT_EQ(count(r.output, "tessera: "), 1) << r.output;
    EXPECT_NE(r.output.find("tessera: error: rank 1 of 2: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("cornell-box.obj"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "img.exr"));
    EXPECT_FALSE(fs::exists(dir_ / "img.png"));
    EXPECT_FALSE(fs::exists(dir_ / "img.ckpt"));
}

TEST_F(DistributedCli, RankWithOtherSettingsIsRefusedNamingIt) {
    // As on a machine with another version of the scene or a mistyped launch line: the
    // passes would not fit together, so the job stops before the first pass.
    const std::string args = " --backend embree --width 16 --height 16 --spp 4 --out " + (dir_ / "img.exr").string();
    const std::string render = std::string(TESSERA_EXE) + " render " + scene("cornell-box.json") + args;
    const auto r = run_shell(kMpirun + " -n 1 " + render + " : -n 1 " + render + " --seed 2");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(count(r.output, "tessera: error"), 1) << r.output;  // after rank 0's banner
    EXPECT_NE(r.output.find("tessera: error: rank 1 of 2: its scene file, scene data or settings differ from rank 0's"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "img.exr"));
}

TEST_F(DistributedCli, WhatDependsOnEarlierPassesIsRefusedOnce) {
    // tic's cache and the igi family's AOV sums carry over from pass to pass.
    const std::vector<std::pair<std::string, std::string>> cases{
        {"--method tic", "tessera: error: --method tic: a distributed render (2 MPI ranks) cannot split its passes"},
        {"--method igi --aov", "tessera: error: --aov with --method igi: a distributed render (2 MPI ranks)"}};
    for (const auto& [args, message] : cases) {
        const auto r = run_shell(kMpirun + " -n 2 " + TESSERA_EXE + " render " + scene("cornell-box.json") +
                                 " --backend embree --spp 2 " + args + " --out " + (dir_ / "img.exr").string());
        EXPECT_EQ(r.exit_code, 2) << r.output;
        EXPECT_EQ(count(r.output, "tessera: "), 1) << r.output;
        EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(dir_ / "img.exr"));
    }
}

TEST_F(DistributedCli, AccuracySweepOverTwoRanksGivesTheSerialErrors) {
    // bench/accuracy --mpi 2: the reference's passes and the three settings spread over two
    // ranks; the reference and every relMSE equal the serial sweep's (timings do not).
    const std::string src = TESSERA_SOURCE_DIR;
    auto sweep = [&](const std::string& name, const std::string& extra) {
        const fs::path out = dir_ / name;
        const std::string cmd = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 python3 " + src +
                                "/bench/accuracy --tessera " + TESSERA_EXE + " --scenes " + scene("cornell-box.json") +
                                " --width 24 --height 24 --frames 2 --reference-spp 64 --methods pt direct" +
                                " --grid pt:spp=1,4 --grid direct:spp=2 --grid direct:shadow-samples=1,4" +
                                " --backends embree --no-flip --out-dir " + out.string() + " --work-dir " +
                                (out / "work").string() + extra;
        const auto r = run_shell(cmd);
        EXPECT_EQ(r.exit_code, 0) << cmd << "\n" << r.output;
        return std::make_pair(file_bytes(out / "work/cornell-box/reference_pt_64spp_24x24.exr"),
                              file_bytes(out / "cornell-box.csv"));
    };
    const auto [ref_mpi, csv_mpi] = sweep("mpi", " --mpi 2");
    const auto [ref_serial, csv_serial] = sweep("serial", "");
    ASSERT_GT(ref_serial.size(), 1000u);
    EXPECT_TRUE(ref_mpi == ref_serial);
    // Every CSV column but the timings (median_pass_s, time_s: fields 6 and 7), line by line.
    auto without_timings = [](const std::string& csv) {
        std::vector<std::string> lines;
        std::istringstream in(csv);
        for (std::string line; std::getline(in, line);) {
            std::istringstream fields(line);
            std::string kept, field;
            for (int i = 0; std::getline(fields, field, ','); ++i)
                if (i != 6 && i != 7) kept += field + ",";
            lines.push_back(kept);
        }
        return lines;
    };
    EXPECT_EQ(without_timings(csv_mpi).size(), 5u) << "header, 2 pt and 2 direct rows";
    EXPECT_EQ(without_timings(csv_mpi), without_timings(csv_serial));
}

}  // namespace
