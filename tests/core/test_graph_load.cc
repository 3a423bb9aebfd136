// Graph loading: the good graph loads in topological order, every file of the bad-graph
// corpus is refused with an error naming its place, and edits validate like loading.
// The registry is built here with stand-ins for the built-in nodes (same names, ports and
// parameters), so these tests depend on the loader alone.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/Error.h"
#include "core/Graph.h"
#include "core/JsonParse.h"
#include "core/Node.h"
#include "core/Registry.h"

namespace cg {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

const fs::path kData = fs::path(CLOUDGRAPH_SOURCE_DIR) / "tests" / "data";

class NeverCooks final : public Node {
public:
    void cook(CookContext&) override { throw std::logic_error("the loader must not cook"); }
};

ParamDecl param(std::string name, ParamValue def, std::optional<double> min = std::nullopt,
                std::optional<double> max = std::nullopt)
{
    ParamDecl p;
    p.name = std::move(name);
    p.type = paramTypeOf(def);
    p.defaultValue = std::move(def);
    p.doc = "test parameter";
    p.min = min;
    p.max = max;
    return p;
}

PortDecl port(std::string name, std::string type, bool optional = false)
{
    return PortDecl{std::move(name), std::move(type), "test port", optional};
}

NodeDecl node(std::string type, std::vector<PortDecl> in, std::vector<PortDecl> out,
              std::vector<ParamDecl> params)
{
    NodeDecl d;
    d.type = std::move(type);
    d.doc = "stand-in for the built-in node";
    d.inputs = std::move(in);
    d.outputs = std::move(out);
    d.params = std::move(params);
    d.create = [] { return std::make_unique<NeverCooks>(); };
    return d;
}

/// The built-in util nodes as declarations only.
const Registry& testRegistry()
{
    static const Registry registry = [] {
        Registry r;
        registerCoreDataTypes(r);
        const double maxSize = 1099511627776.0;  // 2^40
        r.addNode(node("Constant", {}, {port("value", "Float")}, {param("value", 1.0)}));
        NodeDecl osc =
            node("Oscillator", {}, {port("value", "Float")},
                 {param("amplitude", 1.0), param("period", 24.0, 1e-6), param("offset", 1.0)});
        osc.frameDependent = true;
        r.addNode(std::move(osc));
        NodeDecl field =
            node("RandomField", {}, {port("values", "FloatArray")},
                 {param("width", std::int64_t(64), 1, maxSize),
                  param("height", std::int64_t(64), 1, maxSize), param("seed", std::int64_t(0), 0),
                  param("low", 0.0), param("high", 1.0)});
        field.validate = [](const ParamSet& p, const ParamChecker& check) {
            check.checkAllocation("width", {p.getInt("width"), p.getInt("height")}, 4);
        };
        r.addNode(std::move(field));
        r.addNode(node("Scale", {port("values", "FloatArray"), port("factor", "Float", true)},
                       {port("values", "FloatArray")}, {param("factor", 1.0)}));
        r.addNode(node("Sum", {port("a", "FloatArray"), port("b", "FloatArray")},
                       {port("values", "FloatArray")}, {}));
        NodeDecl integrate = node("Integrate", {port("rate", "FloatArray")},
                                  {port("state", "FloatArray")}, {param("initial", 0.0)});
        integrate.simulation = true;
        r.addNode(std::move(integrate));
        r.addNode(node("Statistics", {port("values", "FloatArray")},
                       {port("mean", "Float"), port("min", "Float"), port("max", "Float"),
                        port("count", "Int"), port("summary", "Text")},
                       {}));
        ParamDecl arrayFile = param("file", std::string("values.####.txt"));
        arrayFile.role = ParamRole::OutputPath;
        NodeDecl writeArray = node("WriteArray", {port("values", "FloatArray")},
                                   {port("files", "Text")}, {arrayFile});
        writeArray.writesFiles = true;
        r.addNode(std::move(writeArray));
        ParamDecl textFile = param("file", std::string("summary.####.txt"));
        textFile.role = ParamRole::OutputPath;
        NodeDecl writeText =
            node("WriteText", {port("text", "Text")}, {port("files", "Text")}, {textFile});
        writeText.writesFiles = true;
        r.addNode(std::move(writeText));
        return r;
    }();
    return registry;
}

std::string readFile(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// what() of the InputError from loading, or a failure text if none (or another) was thrown.
std::string loadError(const fs::path& path, const LoadOptions& options = {})
{
    try {
        loadGraph(path, testRegistry(), options);
    } catch (const InputError& e) {
        return e.what();
    } catch (const std::exception& e) {
        return std::string("<not an InputError: ") + e.what() + ">";
    }
    return "<loaded without error>";
}

std::string parseError(const std::string& text, const LoadOptions& options = {})
{
    try {
        parseGraph(text, "t.json", testRegistry(), options);
    } catch (const InputError& e) {
        return e.what();
    }
    return "<loaded without error>";
}

std::vector<std::string> orderOf(const Graph& g)
{
    std::vector<std::string> ids;
    for (std::size_t i : g.topologicalOrder()) ids.push_back(g.nodes()[i].id);
    return ids;
}

TEST(GraphLoad, ChainLoadsInTopologicalOrder)
{
    const Graph g = loadGraph(kData / "good" / "chain.json", testRegistry());
    EXPECT_EQ(g.source, kData / "good" / "chain.json");
    EXPECT_EQ(g.frames.start, 0);
    EXPECT_EQ(g.frames.end, 5);
    EXPECT_EQ(g.timeStep, 0.5);
    EXPECT_EQ(g.seed, 7u);
    ASSERT_EQ(g.nodes().size(), 5u);
    // Sorted by id.
    EXPECT_EQ(g.nodes()[0].id, "field");
    EXPECT_EQ(g.nodes()[4].id, "write");
    EXPECT_EQ(orderOf(g),
              (std::vector<std::string>{"field", "scale", "integrate", "stats", "write"}));
    EXPECT_EQ(g.find("field")->params.getInt("width"), 16);
    EXPECT_EQ(g.find("field")->params.getFloat("high"), 1.0);  // default
    EXPECT_EQ(g.find("scale")->inputs.at("values").node, "field");
    EXPECT_EQ(g.upstream()[g.indexOf("integrate")], (std::vector<std::size_t>{g.indexOf("scale")}));
    EXPECT_EQ(g.sinks(), (std::vector<std::size_t>{g.indexOf("write")}));
    EXPECT_THROW(g.indexOf("nope"), std::out_of_range);
    EXPECT_EQ(g.find("nope"), nullptr);
}

TEST(GraphLoad, TiesInTheOrderGoById)
{
    const Graph g = parseGraph(R"({"cloudgraph": 1, "nodes": {
        "z": {"type": "RandomField"}, "a": {"type": "RandomField"},
        "m": {"type": "Sum", "inputs": {"a": "z.values", "b": "a.values"}},
        "b": {"type": "Scale", "inputs": {"values": "z.values"}}}})",
                               "t.json", testRegistry());
    EXPECT_EQ(orderOf(g), (std::vector<std::string>{"a", "z", "b", "m"}));
    EXPECT_EQ(g.upstream()[g.indexOf("m")],
              (std::vector<std::size_t>{g.indexOf("a"), g.indexOf("z")}));
}

TEST(GraphLoad, BadCorpusIsRefusedWithItsPlace)
{
    const fs::path dir = kData / "bad";
    const Json expected = Json::parse(readFile(dir / "expected.json"));
    std::set<std::string> files;
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.path().extension() == ".json" && entry.path().filename() != "expected.json")
            files.insert(entry.path().filename().string());
    for (const std::string& f : files)
        EXPECT_TRUE(expected.contains(f)) << f << " has no entry in expected.json";
    for (const auto& item : expected.items()) {
        SCOPED_TRACE(item.key());
        ASSERT_TRUE(files.count(item.key())) << "expected.json names a missing file";
        const std::string what = loadError(dir / item.key());
        ASSERT_FALSE(item.value().at("contains").empty());
        for (const Json& s : item.value().at("contains"))
            EXPECT_NE(what.find(s.get<std::string>()), std::string::npos)
                << "error: " << what << "\nshould contain: " << s.get<std::string>();
    }
    EXPECT_GE(files.size(), 25u);
}

TEST(GraphLoad, FileLevelErrors)
{
    EXPECT_EQ(loadError(kData / "bad" / "no_such_file.json")
                  .rfind((kData / "bad" / "no_such_file.json").string() + ": cannot read", 0),
              0u);
    LoadOptions small;
    small.maxFileBytes = 10;
    const std::string tooBig = loadError(kData / "good" / "chain.json", small);
    EXPECT_NE(tooBig.find("chain.json: file is"), std::string::npos) << tooBig;
    EXPECT_NE(tooBig.find("over the limit of 10 bytes"), std::string::npos) << tooBig;
    EXPECT_NE(parseError(std::string(11, ' '), small).find("over the limit"), std::string::npos);
}

TEST(GraphLoad, LimitsComeFromOptions)
{
    const std::string escape = readFile(kData / "bad" / "output_path_escape.json");
    LoadOptions allow;
    allow.allowPathsOutsideOut = true;
    const Graph g = parseGraph(escape, "t.json", testRegistry(), allow);
    EXPECT_EQ(g.find("w")->params.getString("file"), "../x.txt");
    EXPECT_TRUE(g.limits.allowPathsOutsideOut);

    const std::string big = R"({"cloudgraph": 1, "nodes": {"f": {"type": "RandomField",
        "params": {"width": 1000, "height": 1000}}}})";
    LoadOptions tight;
    tight.allocationLimitBytes = 1000;
    EXPECT_EQ(parseError(big, tight),
              "t.json:/nodes/f/params/width: would allocate 4000000 bytes, over the limit of "
              "1000 bytes (node 'f')");
    EXPECT_NO_THROW(parseGraph(big, "t.json", testRegistry()));

    LoadOptions shallow;
    shallow.maxJsonDepth = 2;
    EXPECT_EQ(parseError(R"({"cloudgraph": 1, "nodes": {"c": {"type": "Constant"}}})", shallow),
              "t.json:/nodes/c: JSON nests deeper than 2 levels");
}

TEST(GraphLoad, StrictJson)
{
    EXPECT_EQ(parseJsonStrict(R"({"a": [1, {"b": 2}]})", "x", 8),
              Json::parse(R"({"a": [1, {"b": 2}]})"));
    try {
        parseJsonStrict("{\"a\": [1, {\"b\": 2, \"b\": 3}]}", "x.json", 8);
        FAIL() << "duplicate key accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(e.where(), "x.json:/a/1/b");
        EXPECT_EQ(e.message(), "duplicate key 'b'");
    }
    try {
        parseJsonStrict("{\n  \"a\": tru\n}", "x.json", 8);
        FAIL() << "bad literal accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(e.where().rfind("x.json:line 2, column ", 0), 0u) << e.what();
        EXPECT_NE(e.where().find("(byte "), std::string::npos) << e.what();
    }
    // Depth 200,000 is refused at the limit without recursing.
    const std::string deep(200000, '[');
    EXPECT_THROW(parseJsonStrict(deep, "x", 64), InputError);
    EXPECT_THROW(parseJsonStrict("{} {}", "x", 8), InputError);
    EXPECT_EQ(jsonPointerToken("a/b~c"), "a~1b~0c");
}

TEST(GraphLoad, SetParamValidatesAndLeavesTheGraphOnError)
{
    Graph g = loadGraph(kData / "good" / "chain.json", testRegistry());
    g.setParam("scale", "factor", Json(3.0));
    EXPECT_EQ(g.find("scale")->params.getFloat("factor"), 3.0);

    try {
        g.setParam("field", "width", Json("wide"));
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("chain.json:/nodes/field/params/width"),
                  std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("(node 'field')"), std::string::npos) << e.what();
    }
    EXPECT_EQ(g.find("field")->params.getInt("width"), 16);
    // In range for the parameter, but over the allocation limit with the other size.
    EXPECT_THROW(g.setParam("field", "width", Json(std::int64_t(1) << 40), "here"), InputError);
    EXPECT_EQ(g.find("field")->params.getInt("width"), 16);
    EXPECT_THROW(g.setParam("write", "file", Json("../up.txt")), InputError);
    EXPECT_EQ(g.find("write")->params.getString("file"), "stats/summary.####.txt");
    EXPECT_THROW(g.setParam("nope", "x", Json(1)), InputError);
    EXPECT_THROW(g.setParam("field", "nope", Json(1)), InputError);
}

std::string overrideError(Graph& g, const std::string& assignment)
{
    try {
        applySetOverride(g, assignment);
    } catch (const InputError& e) {
        return e.what();
    }
    return "<accepted>";
}

TEST(GraphLoad, SetOverride)
{
    Graph g = loadGraph(kData / "good" / "chain.json", testRegistry());
    applySetOverride(g, "field.width=32");
    EXPECT_EQ(g.find("field")->params.getInt("width"), 32);
    applySetOverride(g, "write.file=out/s.####.txt");  // not JSON: taken as a string
    EXPECT_EQ(g.find("write")->params.getString("file"), "out/s.####.txt");
    applySetOverride(g, "write.file=\"a=b.txt\"");  // JSON string; only the first '=' splits
    EXPECT_EQ(g.find("write")->params.getString("file"), "a=b.txt");

    EXPECT_EQ(overrideError(g, "field.width=2.5"),
              "--set field.width: expected an integer, got 2.5 (node 'field')");
    EXPECT_EQ(overrideError(g, "field.widht=3"),
              "--set field.widht: unknown parameter 'widht'; did you mean 'width'? (node 'field')");
    EXPECT_EQ(overrideError(g, "feild.width=3"),
              "--set feild.width: unknown node 'feild'; did you mean 'field'?");
    const std::string big = overrideError(g, "field.height=1099511627776");
    EXPECT_EQ(big.rfind("--set field.height: ", 0), 0u) << big;
    EXPECT_NE(big.find("(node 'field')"), std::string::npos) << big;
    EXPECT_EQ(g.find("field")->params.getInt("height"), 8);
    EXPECT_EQ(overrideError(g, "write.file=/etc/x"),
              "--set write.file: output path '/etc/x' escapes the output directory "
              "(use --allow-outside-out to permit) (node 'write')");
    EXPECT_EQ(overrideError(g, "field=3"), "--set field: expected node.param=value, got 'field=3'");
    EXPECT_EQ(overrideError(g, "field.width"),
              "--set field.width: expected node.param=value, got 'field.width'");
}

TEST(GraphLoad, GraphToJsonRoundTrips)
{
    Graph g = loadGraph(kData / "good" / "chain.json", testRegistry());
    applySetOverride(g, "field.low=-0.5");
    const Json j = graphToJson(g);
    EXPECT_EQ(j.at("cloudgraph"), 1);
    EXPECT_EQ(j.at("frames"), Json::parse(R"({"start": 0, "end": 5})"));
    // Only parameters that differ from their defaults are written.
    EXPECT_EQ(j.at("nodes").at("field").at("params"),
              Json::parse(R"({"width": 16, "height": 8, "seed": 3, "low": -0.5})"));
    EXPECT_FALSE(j.at("nodes").at("stats").contains("params"));
    EXPECT_EQ(j.at("nodes").at("stats").at("inputs").at("values"), "integrate.state");
    EXPECT_EQ(j.at("nodes").at("stats").at("position"), Json::parse("[296, -40]"));
    EXPECT_FALSE(j.at("nodes").at("field").contains("position"));

    const Graph back = parseGraph(j.dump(2), "saved.json", testRegistry());
    EXPECT_EQ(graphToJson(back), j);
    EXPECT_EQ(back.description, g.description);
    EXPECT_EQ(back.timeStep, g.timeStep);
    EXPECT_EQ(back.seed, g.seed);
    ASSERT_EQ(back.nodes().size(), g.nodes().size());
    for (std::size_t i = 0; i < g.nodes().size(); ++i) {
        const GraphNode& a = g.nodes()[i];
        const GraphNode& b = back.nodes()[i];
        EXPECT_EQ(a.id, b.id);
        EXPECT_EQ(a.decl, b.decl);
        EXPECT_EQ(a.comment, b.comment);
        EXPECT_EQ(a.position, b.position);
        EXPECT_EQ(a.inputs.size(), b.inputs.size());
        for (std::size_t k = 0; k < a.decl->params.size(); ++k)
            EXPECT_EQ(a.params.valueAt(k), b.params.valueAt(k)) << a.id << " param " << k;
    }
    EXPECT_EQ(orderOf(back), orderOf(g));
}

}  // namespace
}  // namespace cg
