// Rendering in chunks, as a Slurm job array does (docs/farm.md): chunked runs equal a full
// run; a chunk starts from the latest cached simulation state; a rerun skips the frames
// whose files verify; bad chunk values are refused before anything cooks; `farm` writes
// scripts that queue each job after the one before, and refuses a value that would break out
// of its line in them before writing anything. The real cluster: tests/farm.

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <functional>

#include <nlohmann/json.hpp>

#include "cli/SlurmScripts.h"
#include "core/Error.h"
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

/// Runs in `dir` until destroyed: `farm` takes its jobs' working directory from its own.
class WorkingDirectory {
public:
    explicit WorkingDirectory(const fs::path& dir) : mBefore(fs::current_path())
    {
        fs::current_path(dir);
    }
    ~WorkingDirectory() { fs::current_path(mBefore); }
    WorkingDirectory(const WorkingDirectory&) = delete;
    WorkingDirectory& operator=(const WorkingDirectory&) = delete;

private:
    fs::path mBefore;
};

/// A farm job whose every value is safe, for the tests to spoil one value at a time.
cli::FarmJob goodJob()
{
    cli::FarmJob job;
    job.name = "shot";
    job.cloudgraph = "/opt/cloudgraph/bin/cloudgraph";
    job.runArgs = {"/shots/shot.json", "--out", "/shots/out", "--set", "field.seed=9"};
    job.farmDir = "/shots/out/slurm";
    job.workDir = "/shots";
    job.chunk = 10;
    job.chunks = 3;
    job.sbatchOptions = {"--partition=render"};
    return job;
}

}  // namespace

TEST(Farm, ChunkedRunsEqualAFullRun)
{
    TempDir dir;
    ASSERT_EQ(runCli({"run", kGraph, "--out", (dir / "full").string(), "-q"}).exitCode, 0);
    const std::string cache = (dir / "cache").string();
    ASSERT_EQ(runCli({"run", kGraph, "--simulations-only", "--cache", cache, "--out",
                      (dir / "chunks").string(), "-q"})
                  .exitCode,
              0);
    EXPECT_FALSE(fs::exists(dir / "chunks")) << "--simulations-only wrote files";
    // 450 frames in chunks of 64: eight tasks, the last one clamped to frames 448..449.
    for (int task = 7; task >= 0; --task) {  // any order: each starts from the cache
        const auto r = runCli({"run", kGraph, "--chunk", "64", "--task", std::to_string(task),
                               "--cache", cache, "--out", (dir / "chunks").string(), "--report",
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
    ASSERT_EQ(
        runCli({"run", kGraph, "--simulations-only", "--frames", "0:379", "--cache", cache, "-q"})
            .exitCode,
        0);
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
        return runCli({"run", kGraph, "--chunk", "10", "--task", "40", "--cache",
                       (dir / "cache").string(), "--out", out.string(), "--report",
                       (dir / report).string(), "-q"});
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

TEST(Farm, ARerunIntoAnEmptiedOutputWritesTheFramesAVideoReadsAgain)
{
    // Before the video's last frame EncodeVideo writes nothing, so its record verifies with
    // no files; that must not spare the frame writer it reads, whose files are gone.
    TempDir dir;
    test::writeFile(dir / "g.json",
                    R"({"cloudgraph": 1, "frames": {"start": 0, "end": 3}, "nodes": {
        "a": {"type": "RandomField", "params": {"width": 3, "height": 1}},
        "w": {"type": "WriteArray", "params": {"file": "a.####.txt"}, "inputs": {"values": "a.values"}},
        "video": {"type": "EncodeVideo", "inputs": {"frames": "w.files"},
                  "params": {"images": "a.####.txt", "lastFrame": 3}}}})");
    const fs::path out = dir / "out";
    auto run = [&] {
        return runCli({"run", (dir / "g.json").string(), "--frames", "0:1", "--cache",
                       (dir / "cache").string(), "--out", out.string(), "-q"});
    };
    ASSERT_EQ(run().exitCode, 0);
    const std::string frame1 = readFile(out / "a.0001.txt");
    fs::remove_all(out);
    const auto again = run();
    ASSERT_EQ(again.exitCode, 0) << again.errors;
    EXPECT_TRUE(fs::exists(out / "a.0000.txt"));
    ASSERT_TRUE(fs::exists(out / "a.0001.txt"));
    EXPECT_EQ(readFile(out / "a.0001.txt"), frame1);
}

TEST(Farm, BadChunkValuesAreRefusedBeforeAnythingCooks)
{
    TempDir dir;
    const std::string out = (dir / "out").string();
    const std::string cache = (dir / "cache").string();
    ASSERT_EQ(
        runCli({"run", kGraph, "--simulations-only", "--frames", "0:0", "--cache", cache, "-q"})
            .exitCode,
        0);
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
        {{"--chunk", "50", "--task", "1", "--farm-token", "0123456789abcdef", "--cache", cache},
         "--cache"},
        {{"--chunk", "50", "--task", "1", "--farm-token", "nonsense", "--cache", cache},
         "--farm-token"},
        {{"--chunk", "50", "--task", "1", "--cache", (dir / "a-file" / "cache").string()},
         "a-file"},
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
    const auto last =
        runCli({"run", kGraph, "--out", (dir / "last").string(), "--chunk", "50", "-q"});
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
    const auto r =
        runCli({"farm", kGraph, "--chunk", "100", "--cache", (dir / "cache").string(), "--out",
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
    const auto job =
        runCli({"run", kGraph, "--chunk", "100", "--task", "4", "--cache", (dir / "cache").string(),
                "--out", out.string(), "--farm-token", token, "-q"});
    EXPECT_EQ(job.exitCode, 0) << job.errors;

    EXPECT_EQ(runCli({"farm", kGraph, "--chunk", "10", "--cache", (dir / "c").string(),
                      "--scheduler", "pbs"})
                  .exitCode,
              2);
    EXPECT_EQ(runCli({"farm", kGraph, "--chunk", "10"}).exitCode, 2);                  // no --cache
    EXPECT_EQ(runCli({"farm", kGraph, "--cache", (dir / "c").string()}).exitCode, 2);  // no --chunk
}

TEST(Farm, ScriptValuesWithControlCharactersAreRefusedNamingWhereTheyCameFrom)
{
    ASSERT_NO_THROW(cli::slurmScripts(goodJob()));
    struct Field {
        std::string named;
        std::function<void(cli::FarmJob&, const std::string&)> spoil;
    };
    const std::vector<Field> fields = {
        {"graph file name", [](cli::FarmJob& j, const std::string& bad) { j.name += bad; }},
        {"--out",
         [](cli::FarmJob& j, const std::string& bad) { j.farmDir = "/shots/o" + bad + "/slurm"; }},
        {"working directory", [](cli::FarmJob& j, const std::string& bad) { j.workDir += bad; }},
        {"cloudgraph executable",
         [](cli::FarmJob& j, const std::string& bad) { j.cloudgraph += bad; }},
        {"--sbatch", [](cli::FarmJob& j, const std::string& bad) { j.sbatchOptions[0] += bad; }},
        {"graph file", [](cli::FarmJob& j, const std::string& bad) { j.runArgs[0] += bad; }},
        {"--set", [](cli::FarmJob& j, const std::string& bad) { j.runArgs[4] += bad; }},
    };
    const std::vector<std::string> bads = {"\ntouch PWNED #", "\r",   std::string(1, '\0'),
                                           "\x1b[2J",         "\x7f", "\t"};
    for (const Field& f : fields) {
        for (const std::string& bad : bads) {
            cli::FarmJob job = goodJob();
            f.spoil(job, bad);
            try {
                cli::slurmScripts(job);
                ADD_FAILURE() << f.named << " accepted byte "
                              << int(static_cast<unsigned char>(bad[0]));
            } catch (const InputError& e) {
                EXPECT_EQ(e.where(), f.named) << e.what();
                // The message quotes the value with its control characters spelled out.
                EXPECT_EQ(std::string(e.what()).find_first_of(std::string("\n\r\x1b\x7f\0", 5)),
                          std::string::npos)
                    << e.what();
            }
        }
    }
    // sbatch reads a backslash as an escape in #SBATCH lines, quoted or not.
    for (const Field& f : std::vector<Field>(fields.begin(), fields.begin() + 3)) {
        cli::FarmJob job = goodJob();
        f.spoil(job, "\\");
        EXPECT_THROW(cli::slurmScripts(job), InputError) << f.named;
    }
}

TEST(Farm, APercentSignIsLiteralInEverySbatchValue)
{
    cli::FarmJob job = goodJob();
    job.name = "shot%j";
    job.farmDir = "/shots/50%/slurm";
    job.workDir = "/shots/100%x";
    const std::string simulate = cli::slurmScripts(job).simulate;
    // --job-name and --chdir take '%' literally; --output is a filename pattern, where "%%" is
    // '%' and the log name's own %j stays a pattern.
    EXPECT_NE(simulate.find("#SBATCH --job-name='cloudgraph-simulate-shot%j'\n"), std::string::npos)
        << simulate;
    EXPECT_NE(simulate.find("#SBATCH --output='/shots/50%%/slurm/logs/simulate-%j.log'\n"),
              std::string::npos)
        << simulate;
    EXPECT_NE(simulate.find("#SBATCH --chdir='/shots/100%x'\n"), std::string::npos) << simulate;
}

TEST(Farm, AGraphNameOutOrWorkingDirectoryThatWouldEndASbatchLineIsRefusedBeforeAnythingIsWritten)
{
    TempDir dir;
    const std::string injected = "touch PWNED #";
    for (const std::string& bad : {std::string("\n"), std::string("\r")}) {
        const fs::path graph = dir / ("shot" + bad + injected + ".json");
        fs::copy_file(kGraph, graph, fs::copy_options::overwrite_existing);
        const fs::path odd = dir / ("work" + bad + injected);
        fs::create_directories(odd);
        struct Case {
            std::string named;
            std::string graph;
            std::string out;
            fs::path workDir;
        };
        const std::vector<Case> cases = {
            {"graph file name", graph.string(), (dir / "out").string(), dir.path()},
            {"--out", kGraph, (dir / ("out" + bad + injected)).string(), dir.path()},
            {"working directory", kGraph, (dir / "out").string(), odd},
        };
        for (const Case& c : cases) {
            test::CliResult r;
            {
                WorkingDirectory in(c.workDir);
                r = runCli({"farm", c.graph, "--chunk", "100", "--cache", (dir / "cache").string(),
                            "--out", c.out});
            }
            EXPECT_EQ(r.exitCode, 2) << c.named << ": " << r.errors;
            EXPECT_NE(r.errors.find(c.named), std::string::npos) << r.errors;
            EXPECT_FALSE(fs::exists(c.out)) << c.named << ": a refused farm wrote --out";
            EXPECT_FALSE(fs::exists(dir / "cache"))
                << c.named << ": a refused farm wrote the cache";
        }
    }
}

TEST(Farm, APercentSignInTheGraphNameOutOrWorkingDirectoryIsWrittenLiterally)
{
    TempDir dir;
    const fs::path graph = dir / "shot%j.json";
    fs::copy_file(kGraph, graph);
    const fs::path work = dir / "work%x";
    fs::create_directories(work);
    const fs::path out = dir / "out 50%";
    test::CliResult r;
    {
        WorkingDirectory in(work);
        r = runCli({"farm", graph.string(), "--chunk", "100", "--cache", (dir / "cache").string(),
                    "--out", out.string()});
    }
    ASSERT_EQ(r.exitCode, 0) << r.errors;
    const std::string frames = readFile(out / "slurm/frames.sbatch");
    EXPECT_NE(frames.find("#SBATCH --job-name='cloudgraph-frames-shot%j'\n"), std::string::npos)
        << frames;
    EXPECT_NE(frames.find("#SBATCH --output='" + (dir / "out 50%%").string() +
                          "/slurm/logs/frames-%A_%a.log'\n"),
              std::string::npos)
        << frames;
    EXPECT_NE(frames.find("#SBATCH --chdir='" + work.string() + "'\n"), std::string::npos)
        << frames;
}

}  // namespace cg
