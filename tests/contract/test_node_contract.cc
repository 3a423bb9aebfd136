// Contract checks over every registered node type: constructs with defaults, documented,
// every parameter changes the output key, and a second pull is a cache hit.

#include <gtest/gtest.h>

#include <map>

#include <nlohmann/json.hpp>

#include "core/Evaluator.h"
#include "core/Graph.h"
#include "nodes/Builtin.h"
#include "support/FixtureNodes.h"
#include "support/TestUtil.h"

namespace cg {

namespace {

Registry& builtinRegistry()
{
    static Registry* registry = [] {
        auto* r = new Registry;
        registerBuiltinNodes(*r);
        registerFixtureNodes(*r);  // sources for every core port type
        return r;
    }();
    return *registry;
}

/// Adds a node of `decl` at `id`, wiring each input to a default source node "<id>_<port>"
/// (recursively, for sources that have inputs of their own).
nlohmann::json& addWithSources(const NodeDecl& decl, const std::string& id, nlohmann::json& nodes)
{
    nlohmann::json inputs = nlohmann::json::object();
    for (const PortDecl& in : decl.inputs) {
        std::string port;
        const std::string source = sourceNodeFor(in.type, port);
        if (source.empty()) throw std::runtime_error("no test source for port type " + in.type);
        const NodeDecl* sourceDecl = builtinRegistry().findNode(source);
        if (!sourceDecl) throw std::runtime_error("test source " + source + " is not registered");
        const std::string sourceId = id + "_" + in.name;
        addWithSources(*sourceDecl, sourceId, nodes);
        inputs[in.name] = sourceId + "." + port;
    }
    nodes[id] = {{"type", decl.type}, {"inputs", inputs}};
    return nodes[id];
}

/// A graph with one node of `decl` at id "node", every input wired to default sources.
std::string graphFor(const NodeDecl& decl)
{
    nlohmann::json nodes = nlohmann::json::object();
    addWithSources(decl, "node", nodes);
    return nlohmann::json{{"cloudgraph", 1}, {"nodes", nodes}}.dump();
}

/// Lists whose items come in groups, where one number would be refused: a valid value each.
const std::map<std::string, nlohmann::json>& groupedListExamples()
{
    static const std::map<std::string, nlohmann::json> examples = {
        {"cameraKeys", {0, 0, -4000, 800, 0, 0, 1200, 40}},  // Renderer: 8 numbers a key
        {"heroClouds", {400, 400, 200, 10}},                 // VapourEmitter: 4 a hero
    };
    return examples;
}

/// A valid value different from `p`'s default.
nlohmann::json otherValue(const ParamDecl& p)
{
    if (const auto it = groupedListExamples().find(p.name); it != groupedListExamples().end())
        return it->second;
    // A step inside [min, max]: `step` up or down if it fits, else halfway to a bound.
    auto nudge = [&](double v, double step) {
        if (!p.max || v + step <= *p.max) return v + step;
        if (!p.min || v - step >= *p.min) return v - step;
        return v < *p.max ? (v + *p.max) / 2 : (v + *p.min) / 2;
    };
    switch (p.type) {
        case ParamType::Float:
            return nudge(std::get<double>(p.defaultValue), 0.25);
        case ParamType::Int:
            return static_cast<std::int64_t>(
                nudge(static_cast<double>(std::get<std::int64_t>(p.defaultValue)), 1));
        case ParamType::Bool:
            return !std::get<bool>(p.defaultValue);
        case ParamType::String: {
            const std::string& d = std::get<std::string>(p.defaultValue);
            if (!p.choices.empty()) return p.choices[0] == d ? p.choices.at(1) : p.choices[0];
            return "other_" + d;
        }
        case ParamType::Vector3: {
            Vec3 v = std::get<Vec3>(p.defaultValue);
            v[0] = nudge(v[0], 0.25);
            return v;
        }
        case ParamType::FloatList: {
            auto v = std::get<std::vector<double>>(p.defaultValue);
            if (v.empty())
                v.push_back(p.min.value_or(0.0));
            else
                v[0] = nudge(v[0], 0.25);
            return v;
        }
        case ParamType::IntList: {
            auto v = std::get<std::vector<std::int64_t>>(p.defaultValue);
            if (v.empty())
                v.push_back(static_cast<std::int64_t>(p.min.value_or(0.0)));
            else
                v[0] = static_cast<std::int64_t>(nudge(static_cast<double>(v[0]), 1));
            return v;
        }
    }
    return nullptr;
}

class NodeContract : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(NodeContract, ConstructsWithDefaultsAndIsDocumented)
{
    const NodeDecl* decl = builtinRegistry().findNode(GetParam());
    ASSERT_NE(decl, nullptr);
    EXPECT_NE(decl->create(), nullptr);
    EXPECT_FALSE(decl->doc.empty());
    EXPECT_FALSE(decl->category.empty());
    for (const auto& p : decl->inputs) EXPECT_FALSE(p.doc.empty()) << p.name;
    for (const auto& p : decl->outputs) EXPECT_FALSE(p.doc.empty()) << p.name;
    for (const auto& p : decl->params) EXPECT_FALSE(p.doc.empty()) << p.name;
}

TEST_P(NodeContract, EveryParameterChangesTheKey)
{
    const NodeDecl* decl = builtinRegistry().findNode(GetParam());
    LoadOptions trusted;  // program parameters too: set only by a graph the user trusts
    trusted.allowGraphPrograms = true;
    Graph g = parseGraph(graphFor(*decl), "contract.json", builtinRegistry(), trusted);
    Evaluator ev(builtinRegistry(), {});
    const Key base = ev.key(g, "node", 0);
    for (const ParamDecl& p : decl->params) {
        // An input file's key is its content, and load refuses a file that is not of the
        // node's format: each reader's own tests cover it (e.g. PrimitiveLoad's).
        if (p.role == ParamRole::InputFile) continue;
        const nlohmann::json original = paramToJson(p.defaultValue);
        g.setParam("node", p.name, otherValue(p));
        EXPECT_NE(ev.key(g, "node", 0), base) << "parameter " << p.name << " is not in the key";
        g.setParam("node", p.name, original);
        EXPECT_EQ(ev.key(g, "node", 0), base);
    }
}

TEST_P(NodeContract, EveryInputChangesTheKey)
{
    const NodeDecl* decl = builtinRegistry().findNode(GetParam());
    Graph g = parseGraph(graphFor(*decl), "contract.json", builtinRegistry());
    Evaluator ev(builtinRegistry(), {});
    const Key base = ev.key(g, "node", 0);
    for (const PortDecl& in : decl->inputs) {
        // Edit the first parameter found upstream of this input.
        const std::string prefix = "node_" + in.name;
        const GraphNode* src = nullptr;
        for (const GraphNode& n : g.nodes())
            if (n.id.rfind(prefix, 0) == 0 && !n.decl->params.empty() && !src) src = &n;
        ASSERT_NE(src, nullptr) << "nothing upstream of " << in.name << " has a parameter";
        const ParamDecl& p = src->decl->params[0];
        g.setParam(src->id, p.name, otherValue(p));
        EXPECT_NE(ev.key(g, "node", 0), base) << "input " << in.name << " is not in the key";
        g.setParam(src->id, p.name, paramToJson(p.defaultValue));
    }
}

TEST_P(NodeContract, SecondPullIsACacheHit)
{
    const NodeDecl* decl = builtinRegistry().findNode(GetParam());
    if (decl->quickParams.count("__skipCook")) GTEST_SKIP() << "needs input the test cannot make";
    Graph g = parseGraph(graphFor(*decl), "contract.json", builtinRegistry());
    for (const auto& [name, value] : decl->quickParams)
        g.setParam("node", name, nlohmann::json::parse(value));
    test::TempDir out;
    EvaluatorOptions options;
    options.outDir = out.path();
    Evaluator ev(builtinRegistry(), options);
    ev.pull(g, "node", 0);
    ev.report().clear();
    ev.pull(g, "node", 0);
    for (const CookRecord& r : ev.report().records()) {
        if (r.node != "node") continue;
        // Writers cook on every run by design, so files on disk are always complete; nodes
        // that declare their outputs uncached (cacheInMemory false) cook again.
        const bool cooksAgain = decl->writesFiles || !decl->cacheInMemory;
        EXPECT_EQ(r.status, cooksAgain ? CookStatus::Cooked : CookStatus::MemoryHit);
    }
}

INSTANTIATE_TEST_SUITE_P(Builtin, NodeContract, ::testing::ValuesIn([] {
                             std::vector<std::string> types;
                             Registry r;
                             registerBuiltinNodes(r);
                             for (const NodeDecl* d : r.nodes()) types.push_back(d->type);
                             return types;
                         }()));

}  // namespace cg
