// End-to-end tests of the cloudgraph command: exit codes, messages, caches across runs,
// several processes sharing a cache, killed runs, plugins, the generated reference.

#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>
#include <set>
#include <thread>

#include <nlohmann/json.hpp>

#include "cli/CommandTable.h"
#include "core/CacheBound.h"
#include "support/TestUtil.h"

namespace cg {

using test::dataPath;
using test::readFile;
using test::readJson;
using test::runCli;
using test::TempDir;

namespace {

/// status of each (node, frame) in a run report, e.g. {"n3@0", "cooked"}.
std::map<std::string, std::string> statuses(const nlohmann::json& report)
{
    std::map<std::string, std::string> out;
    for (const auto& r : report["records"])
        out[r["node"].get<std::string>() + "@" + std::to_string(r["frame"].get<int>())] =
            r["status"];
    return out;
}

std::vector<std::filesystem::path> filesUnder(const std::filesystem::path& dir)
{
    std::vector<std::filesystem::path> out;
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
        if (e.is_regular_file()) out.push_back(e.path());
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace

TEST(Cli, HelpAndVersion)
{
    const auto help = runCli({"--help"});
    EXPECT_EQ(help.exitCode, 0);
    EXPECT_NE(help.output.find("cloudgraph run GRAPH"), std::string::npos);
    const auto version = runCli({"--version"});
    EXPECT_EQ(version.exitCode, 0);
    EXPECT_EQ(version.output.rfind("cloudgraph ", 0), 0u);
    EXPECT_EQ(runCli({"frobnicate"}).exitCode, 2);
    EXPECT_EQ(runCli({"run", "--no-such-option", "x.json"}).exitCode, 2);
    EXPECT_EQ(runCli({}).exitCode, 2);  // the overview, on stderr
    const auto helpWord = runCli({"help"});
    EXPECT_EQ(helpWord.exitCode, 0);
    EXPECT_EQ(helpWord.output, help.output);
    for (const cli::CommandSpec& c : cli::commandTable()) {
        EXPECT_FALSE(c.summary.empty()) << c.name;
        EXPECT_NE(help.output.find("cloudgraph " + c.name + " "), std::string::npos) << c.name;
        EXPECT_NE(help.output.find(c.summary), std::string::npos) << c.name;
    }
    EXPECT_EQ(runCli({"help", "frobnicate"}).exitCode, 2);
}

/// The options of each command come from one table (cli/CommandTable.cc) that the parser and
/// the help both read: an option added without a line of help fails here.
TEST(Cli, EveryCommandsHelpListsEachOfItsOptions)
{
    ASSERT_GE(cli::commandTable().size(), 8u);
    for (const cli::CommandSpec& c : cli::commandTable()) {
        std::vector<cli::OptionSpec> options = c.options;
        options.insert(options.end(), cli::commonOptions().begin(), cli::commonOptions().end());
        std::set<std::string> names;
        for (const cli::OptionSpec& o : options) {
            EXPECT_TRUE(names.insert(o.name).second) << c.name << ": " << o.name << " twice";
            EXPECT_FALSE(o.help.empty()) << c.name << ": " << o.name << " has no help";
        }
        const auto help = runCli({c.name, "--help"});
        EXPECT_EQ(help.exitCode, 0) << c.name << ": " << help.errors;
        EXPECT_EQ(help.output.rfind("usage: cloudgraph " + c.name, 0), 0u) << help.output;
        for (const cli::OptionSpec& o : options) {
            // One line: "  --name VALUE   its help".
            const std::string shown = "\n  " + o.name + (o.value.empty() ? "" : " " + o.value);
            const std::size_t at = help.output.find(shown + " ");
            ASSERT_NE(at, std::string::npos) << c.name << " --help lacks " << o.name;
            const std::string line = help.output.substr(at, help.output.find('\n', at + 1) - at);
            EXPECT_NE(line.find(o.help), std::string::npos) << c.name << ": " << line;
        }
        for (const std::vector<std::string>& same :
             {std::vector<std::string>{c.name, "-h"}, {"help", c.name}, {c.name, "x", "--help"}}) {
            const auto r = runCli(same);
            EXPECT_EQ(r.exitCode, 0) << c.name << ": " << r.errors;
            EXPECT_EQ(r.output, help.output) << same.back();
        }
        const auto bad = runCli({c.name, "--no-such-option", "x"});
        EXPECT_EQ(bad.exitCode, 2) << c.name;
        EXPECT_NE(bad.errors.find("unknown option '--no-such-option'"), std::string::npos)
            << bad.errors;
        EXPECT_NE(bad.errors.find("cloudgraph " + c.name + " --help"), std::string::npos)
            << bad.errors;
        EXPECT_TRUE(bad.output.empty()) << bad.output;
    }
    // "--help" as another option's value asks for nothing: the missing graph is the error.
    const auto value = runCli({"run", "missing.json", "--out", "--help"});
    EXPECT_EQ(value.exitCode, 2);
    EXPECT_NE(value.errors.find("missing.json"), std::string::npos) << value.errors;
    const auto noValue = runCli({"run", "missing.json", "--frames"});
    EXPECT_EQ(noValue.exitCode, 2);
    EXPECT_NE(noValue.errors.find("option --frames needs a value A:B"), std::string::npos)
        << noValue.errors;
}

TEST(Cli, BadGraphCorpusIsRefusedWithExitCode2AndALocation)
{
    const auto expected = readJson(dataPath("bad/expected.json"));
    std::size_t checked = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dataPath("bad"))) {
        const std::string name = entry.path().filename().string();
        if (name == "expected.json") continue;
        ASSERT_TRUE(expected.contains(name)) << name << " has no expectation";
        const auto r = runCli({"validate", entry.path().string()});
        EXPECT_EQ(r.exitCode, 2) << name << ": " << r.errors;
        for (const auto& s : expected[name]["contains"])
            EXPECT_NE(r.errors.find(s.get<std::string>()), std::string::npos)
                << name << ": message lacks '" << s.get<std::string>() << "': " << r.errors;
        ++checked;
    }
    EXPECT_GE(checked, 18u);
}

TEST(Cli, ValidateAcceptsTheShippedGraphs)
{
    for (const auto& entry : std::filesystem::directory_iterator(
             std::filesystem::path(CLOUDGRAPH_SOURCE_DIR) / "graphs")) {
        if (entry.path().extension() != ".json") continue;  // soundings/ holds their data
        const auto r = runCli({"validate", entry.path().string()});
        EXPECT_EQ(r.exitCode, 0) << entry.path() << ": " << r.errors;
    }
}

TEST(Cli, SetOverridesOfOneNodeAreCheckedTogether)
{
    // A camera straight overhead needs a new position, look-at and up: valid together, but
    // the position with the old up looks along it. Any order is accepted; a camera that still
    // looks along its up is refused, naming it.
    const std::string graph =
        std::string(CLOUDGRAPH_SOURCE_DIR) + "/graphs/figure6_towering_cumulus.json";
    const std::string position = "render.cameraPosition=[3200,3200,9000]",
                      lookAt = "render.cameraLookAt=[3200,3200,0]", up = "render.cameraUp=[0,1,0]";
    for (const auto& order : {std::vector<std::string>{position, lookAt, up},
                              std::vector<std::string>{up, position, lookAt},
                              std::vector<std::string>{position, up, lookAt}}) {
        std::vector<std::string> args = {"validate", graph};
        for (const std::string& s : order) args.insert(args.end(), {"--set", s});
        const auto r = runCli(args);
        EXPECT_EQ(r.exitCode, 0) << r.errors;
    }
    const auto alongUp = runCli({"validate", graph, "--set", position, "--set", lookAt});
    EXPECT_EQ(alongUp.exitCode, 2);
    EXPECT_NE(alongUp.errors.find("its up is zero or along the view"), std::string::npos)
        << alongUp.errors;
    // The last of two overrides of one parameter wins, as in order.
    const auto twice =
        runCli({"validate", graph, "--set", "render.width=-3", "--set", "render.width=64"});
    EXPECT_EQ(twice.exitCode, 0) << twice.errors;
}

TEST(Cli, OnlyCooksWhatTheNamedNodesNeed)
{
    const test::TempDir dir;
    const std::string graph = std::string(CLOUDGRAPH_SOURCE_DIR) + "/graphs/default.json";
    const auto out = [&](const char* name) { return (dir / name).string(); };
    // The statistics alone: cooked, but no writer runs, so nothing is written.
    auto r = runCli({"run", graph, "--frames", "0:2", "--out", out("a"), "--only", "stats"});
    ASSERT_EQ(r.exitCode, 0) << r.errors;
    EXPECT_FALSE(std::filesystem::exists(dir / "a" / "demo"));
    // The writer: its three files.
    r = runCli({"run", graph, "--frames", "0:2", "--out", out("b"), "--only", "write"});
    ASSERT_EQ(r.exitCode, 0) << r.errors;
    for (const char* f : {"stats.0000.txt", "stats.0001.txt", "stats.0002.txt"})
        EXPECT_TRUE(std::filesystem::exists(dir / "b" / "demo" / f)) << f;
    // A node the graph lacks, or --only with --chunk: refused before anything is made.
    r = runCli({"run", graph, "--out", out("c"), "--only", "writ"});
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.errors.find("no node 'writ'"), std::string::npos) << r.errors;
    r = runCli({"run", graph, "--out", out("c"), "--only", "write", "--chunk", "10"});
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_FALSE(std::filesystem::exists(dir / "c"));
}

TEST(Cli, RunRefusesBadOptionsBeforeCooking)
{
    TempDir dir;
    const std::string graph = dataPath("good/chain5.json").string();
    const std::string out = (dir / "out").string();
    for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
             {"run", graph, "--out", out, "--frames", "0:99"},
             {"run", graph, "--out", out, "--frames", "x"},
             {"run", graph, "--out", out, "--set", "n3.factr=2"},
             {"run", graph, "--out", out, "--set", "nope.factor=2"},
             {"run", graph, "--out", out, "--set", "n1.width=-5"},
             {"run", graph, "--out", out, "--set", "n5.file=../escape.txt"},
             {"run", graph, "--out", out, "--threads", "0"}}) {
        const auto r = runCli(args);
        EXPECT_EQ(r.exitCode, 2) << args[4] << " " << args[5] << ": " << r.errors;
    }
    EXPECT_FALSE(std::filesystem::exists(out)) << "a refused run wrote files";
    const auto typo = runCli({"run", graph, "--out", out, "--set", "n3.factr=2"});
    EXPECT_NE(typo.errors.find("n3"), std::string::npos) << typo.errors;
    EXPECT_NE(typo.errors.find("factr"), std::string::npos) << typo.errors;
}

TEST(Cli, EditingNode3CooksExactly3To5AcrossRunsSharingACache)
{
    TempDir dir;
    const std::string graph = dataPath("good/chain5.json").string();
    const auto common = std::vector<std::string>{
        "run",      graph, "--cache", (dir / "cache").string(), "--out", (dir / "out").string(),
        "--frames", "0:0"};
    auto first = common;
    first.insert(first.end(), {"--report", (dir / "r1.json").string()});
    ASSERT_EQ(runCli(first).exitCode, 0);
    for (const auto& [k, v] : statuses(readJson(dir / "r1.json"))) EXPECT_EQ(v, "cooked") << k;

    auto second = common;
    second.insert(second.end(), {"--report", (dir / "r2.json").string(), "--set", "n3.factor=5"});
    const auto r = runCli(second);
    ASSERT_EQ(r.exitCode, 0) << r.errors;
    const auto report = readJson(dir / "r2.json");
    const auto s = statuses(report);
    EXPECT_EQ(s.at("n1@0"), "disk-hit");
    EXPECT_EQ(s.at("n2@0"), "disk-hit");
    EXPECT_EQ(s.at("n3@0"), "cooked");
    EXPECT_EQ(s.at("n4@0"), "cooked");
    EXPECT_EQ(s.at("n5@0"), "cooked");
    EXPECT_EQ(report["totals"]["cooked"], 3);
    for (const auto& rec : report["records"]) {
        if (rec["node"] == "n3") {
            EXPECT_EQ(rec["reason"], "parameter 'factor' changed (3 -> 5)");
        }
        if (rec["node"] == "n4") {
            EXPECT_EQ(rec["reason"], "input 'rate' changed");
        }
    }
}

TEST(Cli, CacheLimitPrunesTheCacheAfterTheRunAndNeedsACache)
{
    TempDir dir;
    const std::string graph = dataPath("good/chain5.json").string();
    const std::string cache = (dir / "cache").string();
    const auto run = [&](const std::string& limit, const std::string& report) {
        return runCli({"run", graph, "--cache", cache, "--out", (dir / "out").string(), "--frames",
                       "0:1", "--cache-limit", limit, "--report", report, "-q"});
    };
    ASSERT_EQ(run("1G", (dir / "r1.json").string()).exitCode, 0);
    const CacheUsage before = cacheUsage(cache);
    ASSERT_GT(before.entries, 0u);
    EXPECT_EQ(readJson(dir / "r1.json")["cachePruned"]["entries"], 0);

    ASSERT_EQ(run("0", (dir / "r2.json").string()).exitCode, 0);
    EXPECT_EQ(cacheUsage(cache).entries, 0u);
    EXPECT_EQ(readJson(dir / "r2.json")["cachePruned"]["entries"], before.entries);
    EXPECT_EQ(readJson(dir / "r2.json")["cachePruned"]["bytes"], before.bytes);

    const auto noCache =
        runCli({"run", graph, "--out", (dir / "out").string(), "--cache-limit", "1G"});
    EXPECT_EQ(noCache.exitCode, 2);
    EXPECT_NE(noCache.errors.find("--cache-limit"), std::string::npos) << noCache.errors;
    const auto bad = runCli({"run", graph, "--cache", cache, "--cache-limit", "lots"});
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.errors.find("'lots' is not a size"), std::string::npos) << bad.errors;
}

TEST(Cli, TwoProcessesSharingOneCacheBothSucceedWithIdenticalOutputs)
{
    TempDir dir;
    const std::string graph = dataPath("good/big_field.json").string();
    const std::string cache = (dir / "cache").string();
    test::CliProcess a({"run", graph, "--cache", cache, "--out", (dir / "a").string(), "-q"});
    test::CliProcess b({"run", graph, "--cache", cache, "--out", (dir / "b").string(), "-q"});
    const auto ra = a.wait();
    const auto rb = b.wait();
    ASSERT_EQ(ra.exitCode, 0) << ra.errors;
    ASSERT_EQ(rb.exitCode, 0) << rb.errors;
    for (int f = 0; f <= 3; ++f) {
        const std::string name = "stats.000" + std::to_string(f) + ".txt";
        EXPECT_EQ(readFile(dir / "a" / name), readFile(dir / "b" / name)) << name;
    }
    // A third run is served from the cache and agrees too.
    const auto rc = runCli({"run", graph, "--cache", cache, "--out", (dir / "c").string(),
                            "--report", (dir / "r.json").string()});
    ASSERT_EQ(rc.exitCode, 0) << rc.errors;
    EXPECT_EQ(readFile(dir / "a" / "stats.0003.txt"), readFile(dir / "c" / "stats.0003.txt"));
    const auto report = readJson(dir / "r.json");
    EXPECT_EQ(report["totals"]["cooked"], 4);  // only the writer, once per frame
}

TEST(Cli, RunKilledWhileWritingLeavesNothingThatReadsAsValid)
{
    TempDir dir;
    const std::string graph = dataPath("good/big_field.json").string();
    const std::string cache = (dir / "cache").string();
    ASSERT_EQ(runCli({"run", graph, "--out", (dir / "clean").string(), "-q"}).exitCode, 0);
    for (int delayMs : {30, 120, 250, 400}) {
        test::CliProcess p(
            {"run", graph, "--cache", cache, "--out", (dir / "killed").string(), "-q"});
        std::this_thread::sleep_for(std::chrono::milliseconds(delayMs));
        p.kill(SIGKILL);
        p.wait();
    }
    // Whatever the killed runs left, a new run either trusts complete entries or recooks.
    const auto r =
        runCli({"run", graph, "--cache", cache, "--out", (dir / "after").string(), "-q"});
    ASSERT_EQ(r.exitCode, 0) << r.errors;
    for (int f = 0; f <= 3; ++f) {
        const std::string name = "stats.000" + std::to_string(f) + ".txt";
        EXPECT_EQ(readFile(dir / "clean" / name), readFile(dir / "after" / name)) << name;
    }
    // No half-written output file under a final name: every file present is complete.
    if (std::filesystem::exists(dir / "killed")) {
        for (const auto& f : filesUnder(dir / "killed")) {
            if (f.filename().string()[0] != '.') {
                EXPECT_EQ(readFile(f), readFile(dir / "clean" / f.filename())) << f;
            }
        }
    }
}

TEST(Cli, FailedRunWritesNoPartialFiles)
{
    TempDir dir;
    test::writeFile(dir / "g.json", R"({"cloudgraph": 1, "nodes": {
        "a": {"type": "RandomField", "params": {"width": 3, "height": 1}},
        "b": {"type": "RandomField", "params": {"width": 4, "height": 1}},
        "sum": {"type": "Sum", "inputs": {"a": "a.values", "b": "b.values"}},
        "w": {"type": "WriteArray", "params": {"file": "sum.txt"}, "inputs": {"values": "sum.values"}}}})");
    const auto r = runCli({"run", (dir / "g.json").string(), "--out", (dir / "out").string()});
    EXPECT_EQ(r.exitCode, 2) << r.errors;  // Sum's lengths differ: bad input, named
    EXPECT_NE(r.errors.find("'sum'"), std::string::npos) << r.errors;
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "sum.txt"));
}

TEST(Cli, AFileNameWithoutFrameNumberWrittenOnSeveralFramesIsRefusedAtLoad)
{
    TempDir dir;
    const auto graphWith = [&](const std::string& writer) {
        test::writeFile(dir / "g.json", R"({"cloudgraph": 1, "frames": {"start": 0, "end": 9},
            "nodes": {"a": {"type": "RandomField", "params": {"width": 3, "height": 1}},
                      "w": {"type": "WriteArray", "inputs": {"values": "a.values"},
                            "params": )" + writer +
                                            "}}}");
        return (dir / "g.json").string();
    };
    // Every frame into one name: each would overwrite the last.
    const auto r = runCli({"validate", graphWith(R"({"file": "sum.txt"})")});
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.errors.find("g.json:/nodes/w/params/file"), std::string::npos) << r.errors;
    EXPECT_NE(r.errors.find("no #### frame number"), std::string::npos) << r.errors;
    EXPECT_NE(r.errors.find("(node 'w')"), std::string::npos) << r.errors;
    // The same through --set, and a run is refused before it writes anything.
    const std::string numbered = graphWith(R"({"file": "sum.####.txt"})");
    EXPECT_EQ(runCli({"validate", numbered}).exitCode, 0);
    const auto set =
        runCli({"run", numbered, "--out", (dir / "out").string(), "--set", "w.file=sum.txt"});
    EXPECT_EQ(set.exitCode, 2) << set.errors;
    EXPECT_FALSE(std::filesystem::exists(dir / "out"));
    // Written on one frame only (every 10 over 0..9): one name is right.
    EXPECT_EQ(runCli({"validate", graphWith(R"({"file": "sum.txt", "every": 10})")}).exitCode, 0);
    EXPECT_EQ(runCli({"validate", graphWith(R"({"file": "sum.txt", "every": 9})")}).exitCode, 2);
}

TEST(Cli, PluginNodeCooksAndABadPluginIsRefused)
{
    TempDir dir;
    const auto ok = runCli({"run", dataPath("good/plugin_gain.json").string(), "--plugin",
                            CLOUDGRAPH_SAMPLE_PLUGIN, "--out", dir.path().string()});
    ASSERT_EQ(ok.exitCode, 0) << ok.errors;
    EXPECT_EQ(readFile(dir / "gain.txt"), readFile(dir / "plain.txt"));
    EXPECT_FALSE(readFile(dir / "gain.txt").empty());

    const auto without = runCli({"validate", dataPath("good/plugin_gain.json").string()});
    EXPECT_EQ(without.exitCode, 2);
    EXPECT_NE(without.errors.find("SampleGain"), std::string::npos) << without.errors;

    const auto bad = runCli({"nodes", "--plugin", CLOUDGRAPH_BAD_ABI_PLUGIN});
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.errors.find("ABI version"), std::string::npos) << bad.errors;
    const auto noEntry = runCli({"nodes", "--plugin", CLOUDGRAPH_NO_ENTRY_PLUGIN});
    EXPECT_EQ(noEntry.exitCode, 2);
    EXPECT_NE(noEntry.errors.find("not a CloudGraph plugin"), std::string::npos) << noEntry.errors;
}

TEST(Cli, PluginsLoadFromAbsoluteSearchPathDirectoriesOnly)
{
    TempDir dir;
    std::filesystem::create_directories(dir / "plugins");
    std::filesystem::copy_file(CLOUDGRAPH_SAMPLE_PLUGIN, dir / "plugins" / "libsample.so");
    const char* saved = std::getenv("CLOUDGRAPH_PLUGIN_PATH");
    const std::string savedValue = saved ? saved : "";
    const auto cwd = std::filesystem::current_path();

    ::setenv("CLOUDGRAPH_PLUGIN_PATH", (dir / "plugins").c_str(), 1);
    const auto found = runCli({"nodes", "SampleGain"});
    // A relative entry, even one that names the right directory from here, is ignored.
    std::filesystem::current_path(dir.path());
    ::setenv("CLOUDGRAPH_PLUGIN_PATH", "plugins", 1);
    const auto relative = runCli({"nodes", "SampleGain"});
    std::filesystem::current_path(cwd);
    if (saved) {
        ::setenv("CLOUDGRAPH_PLUGIN_PATH", savedValue.c_str(), 1);
    } else {
        ::unsetenv("CLOUDGRAPH_PLUGIN_PATH");
    }

    EXPECT_EQ(found.exitCode, 0) << found.errors;
    EXPECT_NE(found.output.find("SampleGain"), std::string::npos);
    EXPECT_EQ(relative.exitCode, 2);
    EXPECT_NE(relative.errors.find("not absolute"), std::string::npos) << relative.errors;
}

TEST(Cli, NodeReferenceIsGeneratedAndDocsAreCurrent)
{
    const auto r = runCli({"nodes", "--markdown"});
    ASSERT_EQ(r.exitCode, 0);
    for (const char* type : {"Constant", "Integrate", "RandomField", "WriteText"})
        EXPECT_NE(r.output.find(std::string("## ") + type + "\n"), std::string::npos) << type;
    EXPECT_EQ(readFile(std::filesystem::path(CLOUDGRAPH_SOURCE_DIR) / "docs" / "nodes.md"),
              r.output)
        << "docs/nodes.md is stale: regenerate it with `cloudgraph nodes --markdown > "
           "docs/nodes.md`";
    EXPECT_EQ(runCli({"nodes", "Integrate"}).exitCode, 0);
    EXPECT_EQ(runCli({"nodes", "NoSuchNode"}).exitCode, 2);
}

TEST(Cli, WritersWriteEveryNthFrameFromTheStart)
{
    TempDir dir;
    const auto r = runCli({"run", std::string(CLOUDGRAPH_SOURCE_DIR) + "/graphs/default.json",
                           "--frames", "2:9", "--set", "write.every=3", "--set",
                           "write.file=s.####.txt", "--out", dir.path().string(), "-q"});
    ASSERT_EQ(r.exitCode, 0) << r.errors;
    std::vector<std::string> names;
    for (const auto& f : filesUnder(dir.path())) names.push_back(f.filename().string());
    EXPECT_EQ(names, (std::vector<std::string>{"s.0003.txt", "s.0006.txt", "s.0009.txt"}));
}

TEST(Cli, DotListsNodesAndEdges)
{
    const auto r = runCli({"dot", dataPath("good/chain5.json").string()});
    ASSERT_EQ(r.exitCode, 0) << r.errors;
    EXPECT_NE(r.output.find("digraph"), std::string::npos);
    EXPECT_NE(r.output.find("\"n2\" -> \"n3\""), std::string::npos) << r.output;
}

TEST(Cli, DefaultSceneRunsAndIsIdenticalForOneAndTwoThreads)
{
    TempDir dir;
    const std::string graph = std::string(CLOUDGRAPH_SOURCE_DIR) + "/graphs/default.json";
    for (const char* threads : {"1", "2"}) {
        const auto r = runCli({"run", graph, "--frames", "0:5", "--threads", threads, "--out",
                               (dir / threads).string(), "-q"});
        ASSERT_EQ(r.exitCode, 0) << r.errors;
    }
    const auto one = filesUnder(dir / "1");
    ASSERT_EQ(one.size(), 6u);
    for (const auto& f : one)
        EXPECT_EQ(readFile(f), readFile(dir / "2" / std::filesystem::relative(f, dir / "1")));
}

}  // namespace cg
