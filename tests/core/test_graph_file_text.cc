// graphFileText, what `cloudgraph serve` and the Python module's save() write: the file's
// own key order and spelling are kept, so that saving without an edit changes nothing and
// an edit changes only its own lines.

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/Graph.h"
#include "core/GraphFileText.h"
#include "core/Registry.h"
#include "nodes/Builtin.h"
#include "support/TestUtil.h"

namespace cg {
namespace {

namespace fs = std::filesystem;
using OrderedJson = nlohmann::ordered_json;

class GraphFileTextTest : public ::testing::Test {
protected:
    void SetUp() override { registerBuiltinNodes(registry); }
    Graph parse(const std::string& text) { return parseGraph(text, "test.json", registry); }
    Registry registry;
};

/// The lines only in `after` and only in `before` (as multisets, order kept).
void diffLines(const std::string& before, const std::string& after, std::vector<std::string>& added,
               std::vector<std::string>& removed)
{
    const auto lines = [](const std::string& text) {
        std::vector<std::string> out;
        std::istringstream in(text);
        for (std::string line; std::getline(in, line);) out.push_back(line);
        return out;
    };
    std::vector<std::string> was = lines(before);
    for (const std::string& line : lines(after)) {
        const auto it = std::find(was.begin(), was.end(), line);
        if (it == was.end())
            added.push_back(line);
        else
            was.erase(it);
    }
    removed = was;
}

const char* kGraph = R"({
  "cloudgraph": 1,
  "frames": {"start": 0, "end": 2},
  "nodes": {
    "render": {"type": "Renderer", "inputs": {"volume": "cloud.volume"},
               "params": {"width": 64, "height": 48, "fov": 40,
                          "cameraPosition": [400, -3800, 700]}},
    "cloud": {"type": "SyntheticCumulus", "params": {"voxelSize": 40}}
  }
})";

// Every graph the project ships, saved with no edit: the same keys in the same order with
// the same values (the test compares ordered JSON, so a reordered key fails it).
TEST_F(GraphFileTextTest, SavingWithoutAnEditKeepsEveryShippedGraphAsItWas)
{
    int graphs = 0;
    for (const auto& entry : fs::directory_iterator(fs::path(CLOUDGRAPH_SOURCE_DIR) / "graphs")) {
        if (entry.path().extension() != ".json") continue;
        const std::string text = test::readFile(entry.path());
        const Graph graph = parseGraphFile(text, entry.path(), registry, {});
        const std::string saved = graphFileText(graph, text);
        EXPECT_EQ(OrderedJson::parse(saved), OrderedJson::parse(text)) << entry.path();
        EXPECT_EQ(graphFileText(parseGraphFile(saved, entry.path(), registry, {}), saved), saved)
            << entry.path();
        ++graphs;
    }
    EXPECT_GE(graphs, 10);
}

// Input files are found beside the graph; an edit names them as the file does, and the
// saved file names them so again, wherever the program runs.
TEST_F(GraphFileTextTest, InputFilesStayRelativeToTheGraph)
{
    const fs::path file = fs::path(CLOUDGRAPH_SOURCE_DIR) / "graphs" / "sounding_cumulus.json";
    const std::string text = test::readFile(file);
    Graph graph = parseGraphFile(text, file, registry, {});
    graph.setParam("atmosphere", "soundingFile", "soundings/deep_convection.txt");
    EXPECT_EQ(std::get<std::string>(graph.find("atmosphere")->params.value("soundingFile")),
              (file.parent_path() / "soundings" / "deep_convection.txt").string());
    const OrderedJson saved = OrderedJson::parse(graphFileText(graph, text));
    EXPECT_EQ(saved["nodes"]["atmosphere"]["params"]["soundingFile"],
              "soundings/deep_convection.txt");
    // A command line's --set is relative to the working directory.
    applySetOverride(
        graph, "atmosphere.soundingFile=" +
                   fs::relative(file.parent_path() / "soundings" / "fair_weather.txt").string());
    EXPECT_EQ(OrderedJson::parse(
                  graphFileText(graph, text))["nodes"]["atmosphere"]["params"]["soundingFile"],
              "soundings/fair_weather.txt");
}

TEST_F(GraphFileTextTest, AnEditChangesOnlyItsOwnValue)
{
    Graph graph = parse(kGraph);
    graph.setParam("render", "fov", 55);
    graph.setParam("render", "height", 48);  // unchanged: stays as the file spelled it
    graph.setParam("cloud", "voxelSize", 40.0);
    const OrderedJson saved = OrderedJson::parse(graphFileText(graph, kGraph));
    OrderedJson expected = OrderedJson::parse(kGraph);
    expected["nodes"]["render"]["params"]["fov"] = 55.0;
    EXPECT_EQ(saved, expected);
    // The file's order (render before cloud; width, height, fov, cameraPosition), not sorted.
    EXPECT_EQ(saved["nodes"].begin().key(), "render");
    EXPECT_EQ(saved["nodes"]["render"]["params"].begin().key(), "width");
    EXPECT_EQ(saved["nodes"]["render"].begin().key(), "type");
}

// What `serve` saves after a node was dragged: one new line, the node's position, after
// its last key (whose closing line gains the comma JSON needs).
TEST_F(GraphFileTextTest, MovingANodeAddsOnlyItsPositionLine)
{
    OrderedJson moved = OrderedJson::parse(kGraph);  // what the page sends after a drag
    moved["nodes"]["cloud"]["position"] = {120, -36};
    const Graph graph = parse(moved.dump());
    const std::string before = graphFileText(parse(kGraph), kGraph);
    const std::string after = graphFileText(graph, before);
    std::vector<std::string> added, removed;
    diffLines(before, after, added, removed);
    EXPECT_EQ(added, (std::vector<std::string>{"      },", R"(      "position": [120, -36])"}));
    EXPECT_EQ(removed, (std::vector<std::string>{"      }"}));
    EXPECT_EQ(parse(after).find("cloud")->position, graph.find("cloud")->position);
}

TEST_F(GraphFileTextTest, AParameterSetBackToItsDefaultStaysInTheFile)
{
    Graph graph = parse(kGraph);
    const double fovDefault =
        std::get<double>(graph.find("render")->decl->findParam("fov")->defaultValue);
    graph.setParam("render", "fov", fovDefault);
    const OrderedJson saved = OrderedJson::parse(graphFileText(graph, kGraph));
    EXPECT_EQ(saved["nodes"]["render"]["params"]["fov"], fovDefault);
    EXPECT_FALSE(saved.contains("seed"));  // the file did not say it; it is the default
}

TEST_F(GraphFileTextTest, NewNodesAndKeysFollowTheFilesAndReadTypeFirst)
{
    Graph graph = parse(kGraph);
    graph.setParam("cloud", "baseRadius", 600);
    graph.seed = 9;
    const std::string withWriter = R"({"cloudgraph": 1, "frames": {"start": 0, "end": 2},
      "nodes": {"render": {"type": "Renderer", "inputs": {"volume": "cloud.volume"}},
                "cloud": {"type": "SyntheticCumulus"},
                "write": {"type": "WriteImage", "inputs": {"image": "render.image"},
                          "params": {"file": "a.####.png"}}}})";
    Graph withNode = parse(withWriter);
    const OrderedJson saved = OrderedJson::parse(graphFileText(withNode, kGraph));
    std::vector<std::string> nodes;
    for (const auto& item : saved["nodes"].items()) nodes.push_back(item.key());
    EXPECT_EQ(nodes, (std::vector<std::string>{"render", "cloud", "write"}));
    std::vector<std::string> keys;
    for (const auto& item : saved["nodes"]["write"].items()) keys.push_back(item.key());
    EXPECT_EQ(keys, (std::vector<std::string>{"type", "inputs", "params"}));

    const OrderedJson seeded = OrderedJson::parse(graphFileText(graph, kGraph));
    EXPECT_EQ(seeded["seed"], 9);
    EXPECT_EQ(seeded["nodes"]["cloud"]["params"]["baseRadius"], 600.0);
}

TEST_F(GraphFileTextTest, ArraysOfNumbersStayOnOneLine)
{
    const std::string text = graphFileText(parse(kGraph), "");
    EXPECT_NE(text.find("\"cameraPosition\": [400.0, -3800.0, 700.0]"), std::string::npos) << text;
    EXPECT_NE(text.find("\n  \"nodes\": {\n    \""), std::string::npos) << text;
    EXPECT_LT(text.find("\"start\""), text.find("\"end\""));
}

}  // namespace
}  // namespace cg
