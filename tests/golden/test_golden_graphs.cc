// Golden graphs: the small version of each shipped graph (GoldenSpecs.cc) is cooked and its
// output statistics are compared with tests/golden/expected/<graph>.json.
//   CLOUDGRAPH_GOLDEN_UPDATE=1  rewrites the expected files instead (scripts/update-golden.sh)
//   CLOUDGRAPH_GOLDEN_SET='node.param=value;...'  runs with parameters changed, to see which
//                               statistics a change moves (never with UPDATE)

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <set>
#include <sstream>

#include "golden/GoldenCompare.h"
#include "golden/GoldenRun.h"
#include "golden/GoldenSpecs.h"
#include "support/TestUtil.h"

namespace cg::golden {

namespace {

bool updating()
{
    const char* v = std::getenv("CLOUDGRAPH_GOLDEN_UPDATE");
    return v && std::string(v) == "1";
}

std::vector<std::string> overridesFromEnv()
{
    std::vector<std::string> out;
    const char* v = std::getenv("CLOUDGRAPH_GOLDEN_SET");
    std::istringstream in(v ? v : "");
    for (std::string item; std::getline(in, item, ';');)
        if (!item.empty()) out.push_back(item);
    return out;
}

std::set<std::string> stems(const std::filesystem::path& dir)
{
    std::set<std::string> out;
    if (!std::filesystem::exists(dir)) return out;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        if (e.path().extension() == ".json") out.insert(e.path().stem().string());
    return out;
}

std::vector<std::string> specNames()
{
    std::vector<std::string> names;
    for (const GoldenSpec& s : goldenSpecs()) names.push_back(s.name);
    return names;
}

const char* kHowToUpdate =
    "if the change is intended: CLOUDGRAPH_GOLDEN_UPDATE=1 "
    "build/tests/golden/cloudgraph_golden_tests "
    "(or scripts/update-golden.sh), then review git diff tests/golden/expected (docs/testing.md)";

}  // namespace

class GoldenGraph : public ::testing::TestWithParam<std::string> {};

TEST_P(GoldenGraph, OutputStatisticsMatchTheExpectedFile)
{
    const GoldenSpec* spec = findSpec(GetParam());
    ASSERT_NE(spec, nullptr);
    const std::vector<std::string> overrides = overridesFromEnv();
    ASSERT_FALSE(updating() && !overrides.empty())
        << "CLOUDGRAPH_GOLDEN_SET would be stored as expected";

    const auto start = std::chrono::steady_clock::now();
    const Stats stats = runGolden(*spec, overrides);
    std::cout << spec->name << ": " << stats.size() << " statistics in "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
              << " s\n";
    const nlohmann::json produced = toJson("graphs/" + spec->name + ".json", spec->frames, stats);
    const std::filesystem::path file = expectedDir() / (spec->name + ".json");
    if (updating()) {
        writeExpected(file, produced);
        std::cout << "wrote " << file.string() << "\n";
        return;
    }
    ASSERT_TRUE(std::filesystem::exists(file))
        << "no expected file " << file << "; " << kHowToUpdate;
    const nlohmann::json expected = nlohmann::json::parse(test::readFile(file));
    ASSERT_EQ(expected.at("frames"), produced.at("frames"))
        << spec->name << ": the recorded frames changed; " << kHowToUpdate;
    const std::vector<std::string> problems = compare(stats, expected.at("stats"));
    for (const std::string& p : problems) ADD_FAILURE() << spec->name << ": " << p;
    if (!problems.empty())
        ADD_FAILURE() << spec->name << ": " << problems.size() << " statistics differ; "
                      << kHowToUpdate;
}

INSTANTIATE_TEST_SUITE_P(Shipped, GoldenGraph, ::testing::ValuesIn(specNames()),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                             return param.param;
                         });

TEST(GoldenGraphs, EveryShippedGraphHasAnEntryAndAnExpectedFile)
{
    const std::set<std::string> graphs = stems(graphsDir());
    ASSERT_FALSE(graphs.empty());
    for (const std::string& g : graphs)
        EXPECT_NE(findSpec(g), nullptr)
            << "graphs/" << g << ".json has no small version: add one to "
            << "tests/golden/GoldenSpecs.cc, then " << kHowToUpdate;
    for (const std::string& s : specNames())
        EXPECT_EQ(graphs.count(s), 1u) << "GoldenSpecs.cc names a graph that is gone: " << s;
    if (updating()) return;  // the graph tests are writing them
    for (const std::string& e : stems(expectedDir()))
        EXPECT_EQ(graphs.count(e), 1u)
            << "tests/golden/expected/" << e << ".json belongs to no graph: remove it";
}

// The machinery must be able to fail: a changed parameter of the cheapest graph is reported
// with its frame, node and statistic.
TEST(GoldenGraphs, AChangedParameterIsReportedWithFrameNodeAndStatistic)
{
    const GoldenSpec* spec = findSpec("default");
    ASSERT_NE(spec, nullptr);
    const Stats base = runGolden(*spec);
    const Stats changed = runGolden(*spec, {"wobble.amplitude=0.6"});
    const std::vector<std::string> problems =
        compare(changed, toJson("", spec->frames, base).at("stats"));
    ASSERT_FALSE(problems.empty());
    bool namesState = false;
    for (const std::string& p : problems)
        namesState =
            namesState || p.find("node 'state' output 'state': sum is") != std::string::npos;
    EXPECT_TRUE(namesState) << problems.front();
    for (const std::string& p : problems)
        EXPECT_EQ(p.find("node 'field'"), std::string::npos) << p;  // upstream of the change
}

}  // namespace cg::golden
