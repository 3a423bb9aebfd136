// Rendering in chunks, as a Slurm job array does (docs/farm.md): chunked runs equal a full
// run; a chunk starts from the latest cached simulation state; a rerun skips the frames
// whose files verify; bad chunk values are refused before anything cooks; `farm` writes
// scripts that queue each job after the one before. The real cluster: tests/farm.

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include <nlohmann/json.hpp>

#include "support/TestUtil.h"

namespace cg {

using test::dataPath;
using test::readFile;
using test::readJson;
using test::runCli;
using test::TempDir;

namespace {

namespace fs = std::filesystem;

/// Status of node `node` at each frame of a run report.
std::map<int, std::string> statusesOf(const nlohmann::json& report, const std::string& node)
{
    std::map<int, std::string> out;
    for (const auto& r : report["records"])
        if (r["node"] == node) out[r["frame"].get<int>()] = r["status"];
    return out;
}

const std::string kGraph = dataPath("good/simulation450.json").string();

}  // namespace

TEST(Farm, ChunkedRunsEqualAFullRun)
{
    TempDir dir;
    ASSERT_EQ(runCli({"run", kGraph, "--out", (dir / "full").string(), "-q"}).exitCode, 0);
    const std::string cache = (dir / "cache").string();
    ASSERT_EQ(runCli({"run", kGraph, "--simulations-only", "--cache", cache, "--out", (dir / "chunks").string(),
                      "-q"})
                  .exitCode,
              0);
    EXPECT_FALSE(fs::exists(dir / "chunks")) << "--simulations-only wrote files";
    // 450 frames in chunks of 64: eight tasks, the last one clamped to frames 448..449.
    for (int task = 7; task >= 0; --task) {  // any order: each starts from the cache
        const auto r = runCli({"run", kGraph, "--chunk", "64", "--task", std::to_string(task), "--cache", cache,
                               "--out", (dir / "chunks").string(), "--report",
                               (dir / ("r" + std::to_string(task) + ".json")).string(), "-q"});
        ASSERT_EQ(r.exitCode, 0) << r.errors;
    }
    EXPECT_EQ(readJson(dir / "r7.json")["frames"], nlohmann::json::array({448, 449}));
    std::size_t compared = 0;
    for (const auto& e : fs::directory_iterator(dir / "full")) {
        EXPECT_EQ(readFile(e.path()), readFile(dir / "chunks" / e.path().filename())) << e.path();
        ++compared;
    }
    EXPECT_EQ(compared, 450u);
}

TEST(Farm, AChunkAtFrame400CooksNoSimulationStepBeforeItsLastCachedState)
{
    TempDir dir;
    const std::string cache = (dir / "cache").string();
    // The cache holds the simulation up to frame 379 only.
    ASSERT_EQ(runCli({"run", kGraph, "--simulations-only", "--frames", "0:379", "--cache", cache, "-q"}).exitCode, 0);
    const auto r = runCli({"run", kGraph, "--chunk", "50", "--task", "8", "--cache", cache, "--out",
                           (dir / "out").string(), "--report", (dir / "r.json").string(), "-q"});
    ASSERT_EQ(r.exitCode, 0) << r.errors;
    const auto report = readJson(dir / "r.json");
    EXPECT_EQ(report["frames"], nlohmann::json::array({400, 449}));
    const auto sim = statusesOf(report, "state");
    ASSERT_FALSE(sim.empty());
    EXPECT_EQ(sim.begin()->first, 380) << "stepped from before the last cached state (379)";
    for (const auto& [frame, status] : sim) EXPECT_EQ(status, "cooked") << frame;
    EXPECT_EQ(sim.size(), 70u);  // 380..449: the steps the cache lacked, each once
    EXPECT_EQ(statusesOf(report, "write").size(), 50u);
}

TEST(Farm, ARerunSkipsTheFramesWhoseFilesVerifyAndRedoesTheRest)
{
    TempDir dir;
    const fs::path out = dir / "out";
    auto run = [&](const std::string& report) {
        return runCli({"run", kGraph, "--chunk", "10", "--task", "40", "--cache", (dir / "cache").string(),
                       "--out", out.string(), "--report", (dir / report).string(), "-q"});
    };
    ASSERT_EQ(run("first.json").exitCode, 0);
    const std::string frame403 = readFile(out / "stats.0403.txt");
    fs::remove(out / "stats.0402.txt");
    std::ofstream(out / "stats.0403.txt") << "edited by hand";
    ASSERT_EQ(run("second.json").exitCode, 0);
    const auto report = readJson(dir / "second.json");
    const auto writes = statusesOf(report, "write");
    for (const auto& [frame, status] : writes)
        EXPECT_EQ(status, frame == 402 || frame == 403 ? "cooked" : "verified") << frame;
    // A verified frame cooks nothing upstream of its writer: only 402 and 403 reach the
    // statistics (the simulation steps from the cache to get there).
    EXPECT_EQ(statusesOf(report, "stats").size(), 2u);
    EXPECT_EQ(readFile(out / "stats.0403.txt"), frame403);
    EXPECT_TRUE(fs::exists(out / "stats.0402.txt"));
    EXPECT_EQ(report["totals"]["verified"], 8);
}

TEST(Farm, BadChunkValuesAreRefusedBeforeAnythingCooks)
{
    TempDir dir;
    const std::string out = (dir / "out").string();
    const std::string cache = (dir / "cache").string();
    ASSERT_EQ(runCli({"run", kGraph, "--simulations-only", "--frames", "0:0", "--cache", cache, "-q"}).exitCode, 0);
    std::ofstream(dir / "a-file") << "x";
    struct Case {
        std::vector<std::string> args;
        std::string named;
    };
    const std::vector<Case> cases = {
        {{"--chunk", "0", "--task", "0"}, "--chunk"},
        {{"--chunk", "50", "--task", "9"}, "--task"},  // 450 frames: tasks 0..8
        {{"--chunk", "50"}, "--task"},                 // neither --task nor SLURM_ARRAY_TASK_ID
        {{"--task", "1"}, "--task"},
        {{"--chunk", "50", "--task", "1", "--farm-token", "0123456789abcdef", "--cache", cache}, "--cache"},
        {{"--chunk", "50", "--task", "1", "--farm-token", "nonsense", "--cache", cache}, "--farm-token"},
        {{"--chunk", "50", "--task", "1", "--cache", (dir / "a-file" / "cache").string()}, "a-file"},
        {{"--simulations-only"}, "--simulations-only"},
    };
    for (const Case& c : cases) {
        std::vector<std::string> args = {"run", kGraph, "--out", out};
        args.insert(args.end(), c.args.begin(), c.args.end());
        const auto r = runCli(args);
        EXPECT_EQ(r.exitCode, 2) << c.named << ": " << r.errors;
        EXPECT_NE(r.errors.find(c.named), std::string::npos) << r.errors;
    }
    ::setenv("SLURM_ARRAY_TASK_ID", "seven", 1);
    const auto slurm = runCli({"run", kGraph, "--out", out, "--chunk", "50"});
    ::setenv("SLURM_ARRAY_TASK_ID", "8", 1);
    const auto last = runCli({"run", kGraph, "--out", (dir / "last").string(), "--chunk", "50", "-q"});
    ::unsetenv("SLURM_ARRAY_TASK_ID");
    EXPECT_EQ(slurm.exitCode, 2);
    EXPECT_NE(slurm.errors.find("SLURM_ARRAY_TASK_ID"), std::string::npos) << slurm.errors;
    EXPECT_FALSE(fs::exists(out)) << "a refused run wrote files";
    ASSERT_EQ(last.exitCode, 0) << last.errors;
    EXPECT_TRUE(fs::exists(dir / "last" / "stats.0449.txt"));
    EXPECT_FALSE(fs::exists(dir / "last" / "stats.0399.txt"));
}

TEST(Farm, FarmWritesScriptsThatChainTheJobsAndLeavesATokenInTheCache)
{
    TempDir dir;
    const fs::path out = dir / "out";
    const auto r = runCli({"farm", kGraph, "--chunk", "100", "--cache", (dir / "cache").string(), "--out",
                           out.string(), "--set", "field.seed=9", "--sbatch=--partition=render"});
    ASSERT_EQ(r.exitCode, 0) << r.errors;
    const std::string frames = readFile(out / "slurm/frames.sbatch");
    const std::string simulate = readFile(out / "slurm/simulate.sbatch");
    const std::string submit = readFile(out / "slurm/submit.sh");
    EXPECT_NE(frames.find("#SBATCH --array=0-4\n"), std::string::npos) << frames;  // 450 / 100
    EXPECT_NE(frames.find("#SBATCH --partition=render\n"), std::string::npos);
    // Every #SBATCH line comes before the first command, or sbatch ignores it.
    EXPECT_LT(frames.rfind("#SBATCH"), frames.find("set -euo"));
    EXPECT_NE(frames.find("'--set' 'field.seed=9'"), std::string::npos);
    EXPECT_NE(frames.find("--chunk 100"), std::string::npos);
    EXPECT_NE(simulate.find("--simulations-only"), std::string::npos);
    EXPECT_NE(submit.find("--dependency=afterok:\"$simulate\""), std::string::npos);
    EXPECT_NE(submit.find("--dependency=afterok:\"$frames\""), std::string::npos);
    // The token the jobs are given is in the cache: a job that sees the same directory runs.
    const auto token = frames.substr(frames.find("'--farm-token' '") + 16, 16);
    const auto job = runCli({"run", kGraph, "--chunk", "100", "--task", "4", "--cache", (dir / "cache").string(),
                             "--out", out.string(), "--farm-token", token, "-q"});
    EXPECT_EQ(job.exitCode, 0) << job.errors;

    EXPECT_EQ(runCli({"farm", kGraph, "--chunk", "10", "--cache", (dir / "c").string(), "--scheduler", "pbs"})
                  .exitCode,
              2);
    EXPECT_EQ(runCli({"farm", kGraph, "--chunk", "10"}).exitCode, 2);  // no --cache
    EXPECT_EQ(runCli({"farm", kGraph, "--cache", (dir / "c").string()}).exitCode, 2);  // no --chunk
}

}  // namespace cg
