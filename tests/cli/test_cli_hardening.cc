// End-to-end checks of what an outside audit broke: a graph that runs a program, output
// paths and command-line values that failed late, temporaries left by killed runs.

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <openvdb/io/File.h>
#include <openvdb/tools/LevelSetSphere.h>

#include "support/TestUtil.h"

namespace cg {

using test::runCli;
using test::TempDir;

namespace {

namespace fs = std::filesystem;

/// A graph whose EncodeVideo names `program`; the frames come from a text writer.
std::string graphRunning(const std::string& program)
{
    return R"({"cloudgraph": 1, "frames": {"start": 0, "end": 1}, "nodes": {
        "a": {"type": "RandomField", "params": {"width": 3, "height": 1}},
        "w": {"type": "WriteArray", "params": {"file": "a.####.txt"}, "inputs": {"values": "a.values"}},
        "video": {"type": "EncodeVideo", "inputs": {"frames": "w.files"},
                  "params": {"images": "a.####.txt", "lastFrame": 1, "ffmpeg": ")" +
           program + R"("}}}})";
}

}  // namespace

TEST(CliHardening, AGraphThatNamesAProgramIsRefusedAndTheProgramNeverRuns)
{
    TempDir dir;
    const fs::path marker = dir / "ran";
    test::writeFile(dir / "script.sh", "#!/bin/sh\ntouch '" + marker.string() + "'\n");
    fs::permissions(dir / "script.sh", fs::perms::owner_all);
    test::writeFile(dir / "g.json", graphRunning((dir / "script.sh").string()));
    const std::string graph = (dir / "g.json").string();

    const auto validate = runCli({"validate", graph});
    EXPECT_EQ(validate.exitCode, 2) << validate.errors;
    EXPECT_NE(validate.errors.find("/nodes/video/params/ffmpeg"), std::string::npos)
        << validate.errors;
    const auto run = runCli({"run", graph, "--out", (dir / "out").string(), "-q"});
    EXPECT_EQ(run.exitCode, 2) << run.errors;
    EXPECT_FALSE(fs::exists(marker)) << "the graph's program ran";

    // The user may opt in; then the program the graph names is the one that runs.
    const auto trusted =
        runCli({"run", graph, "--out", (dir / "out").string(), "-q", "--allow-graph-programs"});
    EXPECT_TRUE(fs::exists(marker)) << trusted.errors;
}

TEST(CliHardening, NumericOptionsAreWholeNumbersInRange)
{
    TempDir dir;
    const std::string graph = test::dataPath("good/chain.json").string();
    const std::vector<std::vector<std::string>> bad = {{"--cache-memory-mb", "-1"},
                                                       {"--cache-memory-mb", "5abc"},
                                                       {"--cache-memory-mb", "99999999999999"},
                                                       {"--cache-memory-mb", ""},
                                                       {"--threads", "0"},
                                                       {"--threads", "2x"},
                                                       {"--threads", " 2"},
                                                       {"--frames", "0:x"},
                                                       {"--frames", "+0"},
                                                       {"--frames", "0:99999999999999999999"}};
    for (const auto& option : bad) {
        std::vector<std::string> args = {"run", graph, "--out", (dir / "out").string()};
        args.insert(args.end(), option.begin(), option.end());
        const auto r = runCli(args);
        EXPECT_EQ(r.exitCode, 2) << option[0] << " " << option[1] << ": " << r.errors;
        EXPECT_NE(r.errors.find(option[0]), std::string::npos) << r.errors;
    }
    EXPECT_FALSE(fs::exists(dir / "out"));
    EXPECT_EQ(runCli({"run", graph, "--out", (dir / "out").string(), "--cache-memory-mb", "64",
                      "--threads", "2", "-q"})
                  .exitCode,
              0);
}

TEST(CliHardening, OutAndReportLocationsAreCheckedBeforeCooking)
{
    TempDir dir;
    const std::string graph = test::dataPath("good/chain.json").string();
    test::writeFile(dir / "a-file", "x");
    const auto outIsFile = runCli({"run", graph, "--out", (dir / "a-file").string()});
    EXPECT_EQ(outIsFile.exitCode, 2) << outIsFile.errors;
    EXPECT_NE(outIsFile.errors.find("--out"), std::string::npos) << outIsFile.errors;

    fs::create_directories(dir / "reports");
    const auto reportIsDir = runCli(
        {"run", graph, "--out", (dir / "out").string(), "--report", (dir / "reports").string()});
    EXPECT_EQ(reportIsDir.exitCode, 2) << reportIsDir.errors;
    EXPECT_NE(reportIsDir.errors.find("--report"), std::string::npos) << reportIsDir.errors;
    EXPECT_FALSE(fs::exists(dir / "out")) << "cooked before refusing the report path";
}

TEST(CliHardening, AReportThatCannotBeWrittenDoesNotHideTheCookError)
{
    TempDir dir;
    test::writeFile(dir / "g.json", R"({"cloudgraph": 1, "nodes": {
        "a": {"type": "RandomField", "params": {"width": 3, "height": 1}},
        "b": {"type": "RandomField", "params": {"width": 4, "height": 1}},
        "sum": {"type": "Sum", "inputs": {"a": "a.values", "b": "b.values"}}}})");
    // /proc exists and is a directory, but nothing can be created in it, even by root.
    const std::string report = "/proc/cloudgraph-test/report.json";
    const auto failed = runCli(
        {"run", (dir / "g.json").string(), "--out", (dir / "out").string(), "--report", report});
    EXPECT_EQ(failed.exitCode, 2) << failed.errors;
    EXPECT_NE(failed.errors.find("'sum'"), std::string::npos) << failed.errors;
    EXPECT_NE(failed.errors.find("g.json:/nodes/sum"), std::string::npos) << failed.errors;

    const auto ok = runCli({"run", test::dataPath("good/chain.json").string(), "--out",
                            (dir / "out").string(), "--report", report});
    EXPECT_EQ(ok.exitCode, 2) << ok.errors;
    EXPECT_NE(ok.errors.find("--report"), std::string::npos) << ok.errors;
    EXPECT_EQ(ok.errors.find("internal error"), std::string::npos) << ok.errors;
}

TEST(CliHardening, ABadLibraryOnThePluginPathIsSkippedWithAWarning)
{
    TempDir dir;
    fs::create_directories(dir / "plugins");
    fs::copy_file(CLOUDGRAPH_SAMPLE_PLUGIN, dir / "plugins" / "libsample.so");
    fs::copy_file(CLOUDGRAPH_BAD_ABI_PLUGIN, dir / "plugins" / "libbad-abi.so");
    test::writeFile(dir / "plugins" / "libnot-elf.so", "not a library");
    const char* saved = std::getenv("CLOUDGRAPH_PLUGIN_PATH");
    const std::string savedValue = saved ? saved : "";
    ::setenv("CLOUDGRAPH_PLUGIN_PATH", (dir / "plugins").c_str(), 1);
    const auto r = runCli({"nodes", "SampleGain"});
    if (saved)
        ::setenv("CLOUDGRAPH_PLUGIN_PATH", savedValue.c_str(), 1);
    else
        ::unsetenv("CLOUDGRAPH_PLUGIN_PATH");

    EXPECT_EQ(r.exitCode, 0) << r.errors;
    EXPECT_NE(r.output.find("SampleGain"), std::string::npos);
    EXPECT_NE(r.errors.find("libbad-abi.so"), std::string::npos) << r.errors;
    EXPECT_NE(r.errors.find("libnot-elf.so"), std::string::npos) << r.errors;
    // Named on the command line, the same library is an error.
    const auto named = runCli({"nodes", "--plugin", (dir / "plugins" / "libnot-elf.so").string()});
    EXPECT_EQ(named.exitCode, 2) << named.errors;
}

TEST(CliHardening, InputFilesThatCannotBeReadAreRefusedByValidateAndRun)
{
    TempDir dir;
    ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0644), 0);
    fs::create_directories(dir / "a-directory");
    test::writeFile(dir / "corrupt.cgp",
                    "CGPRIM\r\n but not really a primitive file at all......"
                    "................................................");
    for (const std::string& file : std::vector<std::string>{
             "/dev/zero", (dir / "fifo").string(), (dir / "a-directory").string(),
             (dir / "missing.cgp").string(), (dir / "corrupt.cgp").string()}) {
        test::writeFile(dir / "g.json", R"({"cloudgraph": 1, "nodes": {
            "load": {"type": "PrimitiveLoad", "params": {"file": ")" +
                                            file + R"("}}}})");
        for (const std::string command : {"validate", "run"}) {
            std::vector<std::string> args = {command, (dir / "g.json").string()};
            if (command == "run") args.insert(args.end(), {"--out", (dir / "out").string()});
            const auto r = runCli(args);
            EXPECT_EQ(r.exitCode, 2) << command << " " << file << ": " << r.errors;
            EXPECT_NE(r.errors.find("g.json:/nodes/load/params/file"), std::string::npos)
                << r.errors;
            EXPECT_NE(r.errors.find(file), std::string::npos) << r.errors;
            EXPECT_EQ(r.errors.find("internal error"), std::string::npos) << r.errors;
        }
    }
}

TEST(CliHardening, ReadVdbRefusesFilesThatAreNotFogVolumesWithExitCode2)
{
    TempDir dir;
    openvdb::initialize();
    auto fog = openvdb::FloatGrid::create(0.0f);
    fog->setName("density");
    fog->setGridClass(openvdb::GRID_FOG_VOLUME);
    fog->fill(openvdb::CoordBBox({0, 0, 0}, {20, 20, 20}), 0.5f);
    openvdb::io::File((dir / "good.vdb").string()).write({fog});
    const std::string good = test::readFile(dir / "good.vdb");
    test::writeFile(dir / "truncated.vdb", good.substr(0, good.size() - 100));
    auto sphere = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(10.0f, {}, 1.0f);
    sphere->setName("density");
    openvdb::io::File((dir / "level_set.vdb").string()).write({sphere});
    auto smoke = fog->deepCopy();
    smoke->setName("smoke");
    openvdb::io::File((dir / "other_grid.vdb").string()).write({smoke});
    auto nan = fog->deepCopy();
    nan->tree().setValue({3, 4, 5}, std::nanf(""));  // found only when the voxels are read
    openvdb::io::File((dir / "nan.vdb").string()).write({nan});
    // Read from the start of the tree, before its voxels.
    auto background = openvdb::FloatGrid::create(0.5f);
    background->setName("density");
    background->setGridClass(openvdb::GRID_FOG_VOLUME);
    background->fill(openvdb::CoordBBox({0, 0, 0}, {20, 20, 20}), 0.75f);
    openvdb::io::File((dir / "background.vdb").string()).write({background});

    // `validate` refuses what `run` refuses: it reads the voxels of every ReadVDB file.
    for (const std::string name : {"truncated", "level_set", "other_grid", "nan", "background"}) {
        const std::string file = (dir / (name + ".vdb")).string();
        test::writeFile(dir / "g.json", R"({"cloudgraph": 1, "nodes": {
            "read": {"type": "ReadVDB", "params": {"file": ")" +
                                            file + R"("}}}})");
        for (const std::string command : {"validate", "run"}) {
            std::vector<std::string> args = {command, (dir / "g.json").string()};
            if (command == "run") args.insert(args.end(), {"--out", (dir / "out").string()});
            const auto r = runCli(args);
            EXPECT_EQ(r.exitCode, 2) << command << " " << name << ": " << r.errors;
            EXPECT_NE(r.errors.find(name == "nan" ? "g.json:/nodes/read"
                                                  : "g.json:/nodes/read/params/file"),
                      std::string::npos)
                << r.errors;
            EXPECT_NE(r.errors.find(file), std::string::npos) << r.errors;
            EXPECT_NE(r.errors.find("grid 'density'"), std::string::npos) << r.errors;
            EXPECT_EQ(r.errors.find("internal error"), std::string::npos) << r.errors;
        }
    }
    // The good file runs.
    test::writeFile(dir / "g.json", R"({"cloudgraph": 1, "nodes": {
        "read": {"type": "ReadVDB", "params": {"file": "good.vdb"}}}})");
    const auto r = runCli({"run", (dir / "g.json").string(), "--out", (dir / "out").string()});
    EXPECT_EQ(r.exitCode, 0) << r.errors;
}

namespace {

/// Writes RandomField values to `file` (relative to --out) on frames 0 and 1.
std::string graphWriting(const std::string& file)
{
    return R"({"cloudgraph": 1, "frames": {"start": 0, "end": 1}, "nodes": {
        "a": {"type": "RandomField", "params": {"width": 3, "height": 1}},
        "w": {"type": "WriteArray", "params": {"file": ")" +
           file + R"("}, "inputs": {"values": "a.values"}}}})";
}

}  // namespace

TEST(CliHardening, WritersDoNotFollowASymbolicLinkOutOfOut)
{
    TempDir dir;
    const fs::path out = dir / "out";
    fs::create_directories(out);
    fs::create_directories(dir / "elsewhere");
    test::writeFile(dir / "elsewhere/a.0000.txt", "not yours to replace");
    fs::create_symlink(dir / "elsewhere", out / "demo");
    fs::create_symlink("../elsewhere", out / "up");

    for (const std::string file : {"demo/a.####.txt", "up/a.####.txt", "demo/sub/a.####.txt"}) {
        test::writeFile(dir / "g.json", graphWriting(file));
        const auto r = runCli({"run", (dir / "g.json").string(), "--out", out.string(), "-q"});
        EXPECT_EQ(r.exitCode, 2) << file << ": " << r.errors;
        EXPECT_NE(r.errors.find("g.json:/nodes/w/params/file"), std::string::npos) << r.errors;
        EXPECT_NE(r.errors.find("'w'"), std::string::npos) << r.errors;
        EXPECT_NE(r.errors.find("leads outside the output directory"), std::string::npos)
            << r.errors;
        EXPECT_EQ(test::readFile(dir / "elsewhere/a.0000.txt"), "not yours to replace");
        EXPECT_FALSE(fs::exists(dir / "elsewhere/a.0001.txt"));
        EXPECT_FALSE(fs::exists(dir / "elsewhere/sub"));
    }
    // A link that stays inside --out is followed; --allow-outside-out follows any link.
    fs::create_directories(out / "shots/s1");
    fs::create_symlink("shots/s1", out / "current");
    test::writeFile(dir / "g.json", graphWriting("current/a.####.txt"));
    auto r = runCli({"run", (dir / "g.json").string(), "--out", out.string(), "-q"});
    EXPECT_EQ(r.exitCode, 0) << r.errors;
    EXPECT_TRUE(fs::exists(out / "shots/s1/a.0001.txt"));
    test::writeFile(dir / "g.json", graphWriting("demo/a.####.txt"));
    r = runCli(
        {"run", (dir / "g.json").string(), "--out", out.string(), "-q", "--allow-outside-out"});
    EXPECT_EQ(r.exitCode, 0) << r.errors;
    EXPECT_NE(test::readFile(dir / "elsewhere/a.0000.txt"), "not yours to replace");
}

TEST(CliHardening, AnOutThatCannotBeWrittenIsRefusedBeforeCooking)
{
    TempDir dir;
    test::writeFile(dir / "g.json", graphWriting("a.####.txt"));
    const std::string graph = (dir / "g.json").string();
    // /proc is a directory in which nothing can be created, even by root.
    for (const std::string out : {"/proc", "/proc/cloudgraph-out"}) {
        const auto r = runCli({"run", graph, "--out", out, "-q"});
        EXPECT_EQ(r.exitCode, 2) << out << ": " << r.errors;
        EXPECT_NE(r.errors.find("--out " + out), std::string::npos) << r.errors;
        EXPECT_EQ(r.errors.find("internal error"), std::string::npos) << r.errors;
    }
    if (::geteuid() != 0) {  // root writes into a read-only directory
        fs::create_directories(dir / "read-only");
        fs::permissions(dir / "read-only", fs::perms::owner_read | fs::perms::owner_exec);
        const auto r = runCli({"run", graph, "--out", (dir / "read-only").string(), "-q"});
        EXPECT_EQ(r.exitCode, 2) << r.errors;
        EXPECT_NE(r.errors.find("--out"), std::string::npos) << r.errors;
        fs::permissions(dir / "read-only", fs::perms::owner_all);
    }
    // A graph that writes nothing needs no --out.
    test::writeFile(dir / "quiet.json", R"({"cloudgraph": 1, "nodes": {
        "a": {"type": "RandomField", "params": {"width": 3, "height": 1}}}})");
    const auto quiet = runCli({"run", (dir / "quiet.json").string(), "--out", "/proc", "-q"});
    EXPECT_EQ(quiet.exitCode, 0) << quiet.errors;
}

TEST(CliHardening, ADirectoryWhereAnOutputFileGoesIsRefusedBeforeCooking)
{
    TempDir dir;
    const fs::path out = dir / "out";
    test::writeFile(dir / "g.json", graphWriting("a.####.txt"));
    fs::create_directories(out / "a.0001.txt");  // the last frame's file
    const auto r = runCli({"run", (dir / "g.json").string(), "--out", out.string(), "-q"});
    EXPECT_EQ(r.exitCode, 2) << r.errors;
    EXPECT_NE(r.errors.find("g.json:/nodes/w/params/file"), std::string::npos) << r.errors;
    EXPECT_NE(r.errors.find("a.0001.txt"), std::string::npos) << r.errors;
    EXPECT_NE(r.errors.find("is a directory"), std::string::npos) << r.errors;
    EXPECT_FALSE(fs::exists(out / "a.0000.txt")) << "cooked before refusing";

    // Frames outside the range cooked are not in the way.
    const auto first =
        runCli({"run", (dir / "g.json").string(), "--out", out.string(), "-q", "--frames", "0:0"});
    EXPECT_EQ(first.exitCode, 0) << first.errors;
    EXPECT_TRUE(fs::exists(out / "a.0000.txt"));
}

}  // namespace cg
