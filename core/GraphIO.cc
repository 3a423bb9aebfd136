// Reading and writing graph files.
//
// Graph file format, version 1. A graph file is one JSON object (UTF-8, no comments):
//
//   {
//     "cloudgraph": 1,                    required; the format version. Any other value,
//                                         or a missing key, is refused.
//     "description": "...",               optional string
//     "frames": {"start": 0, "end": 47},  optional; each key optional (default 0); integers
//                                         with 0 <= start <= end <= 1000000; end inclusive
//     "timeStep": 1.0,                    optional seconds per frame; a number, 0 < t <= 86400
//     "seed": 0,                          optional integer >= 0 (up to 2^64-1)
//     "nodes": {                          required object, 1 to 10000 nodes
//       "<id>": {
//         "type": "NodeType",             required; a registered node type
//         "params": {"name": value},      optional; unlisted parameters keep their defaults
//         "inputs": {"port": "up.out"},   optional; input port <- output `out` of node `up`
//         "comment": "...",               optional string, kept when the graph is saved
//         "bypass": true,                 optional; a writer writes nothing, another node
//                                         passes its first input through (Graph::checkBypass)
//         "position": [x, y]              optional; where `serve` draws the node, two integers
//                                         within +-1000000 (page pixels); not cooked
//       }
//     }
//   }
//
// Node ids match [A-Za-z_][A-Za-z0-9_-]* and have at most 128 characters.
// Parameter values: float takes any number; int only integers (2.0 is refused); bool only
// true/false; string only strings; vec3 an array of 3 numbers; lists arrays. min/max are
// inclusive. An OutputPath string must be relative and free of ".." components unless
// LoadOptions::allowPathsOutsideOut (--allow-outside-out).
//
// The reader is strict: unknown keys at any level, duplicate keys, numbers that overflow a
// double, nesting deeper than LoadOptions::maxJsonDepth and files over maxFileBytes are all
// errors. Every error is an InputError whose where() is "<file>:<JSON pointer>" (or
// "<file>:line L, column C (byte B)" for syntax errors), and whose message names the node
// concerned as "(node 'id')". Everything is checked before the graph is returned; nothing
// is cooked.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <system_error>

#include <nlohmann/json.hpp>

#include "core/Error.h"
#include "core/Graph.h"
#include "core/JsonParse.h"
#include "core/Registry.h"

namespace cg {

namespace {

using Json = nlohmann::json;

constexpr std::int64_t kMaxFrame = 1000000;
constexpr std::size_t kMaxNodes = 10000;
constexpr std::size_t kMaxIdLength = 128;
constexpr double kMaxTimeStep = 86400.0;
constexpr std::int64_t kMaxPosition = 1000000;

/// Shared by every check of one file: turns a JSON pointer into an error location.
struct Reader {
    const std::string& source;

    std::string at(const std::string& pointer) const { return source + ":" + pointer; }
    [[noreturn]] void fail(const std::string& pointer, const std::string& message) const
    {
        throw InputError(at(pointer), message);
    }

    /// Refuses keys of `object` outside `allowed`, naming the first by its pointer.
    void onlyKeys(const Json& object, const std::string& pointer,
                  const std::vector<std::string>& allowed) const
    {
        for (const auto& item : object.items()) {
            if (std::find(allowed.begin(), allowed.end(), item.key()) == allowed.end()) {
                fail(pointer + "/" + jsonPointerToken(item.key()),
                     "unknown key '" + item.key() + "'" + didYouMean(item.key(), allowed));
            }
        }
    }
    const Json& object(const Json& j, const std::string& pointer, const std::string& what) const
    {
        if (!j.is_object()) fail(pointer, what + " must be a JSON object");
        return j;
    }
    std::int64_t integer(const Json& j, const std::string& pointer, const std::string& what,
                         std::int64_t lo, std::int64_t hi) const
    {
        if (!j.is_number_integer()) fail(pointer, what + " must be an integer, got " + j.dump());
        if ((j.is_number_unsigned() && j.get<std::uint64_t>() > static_cast<std::uint64_t>(hi)) ||
            (!j.is_number_unsigned() && (j.get<std::int64_t>() < lo || j.get<std::int64_t>() > hi)))
            fail(pointer, what + " " + j.dump() + " is outside [" + std::to_string(lo) + ", " +
                              std::to_string(hi) + "]");
        return j.get<std::int64_t>();
    }
};

bool validId(const std::string& id)
{
    if (id.empty() || id.size() > kMaxIdLength) return false;
    auto alpha = [](char c) {
        return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_';
    };
    if (!alpha(id[0])) return false;
    for (char c : id)
        if (!alpha(c) && !(c >= '0' && c <= '9') && c != '-') return false;
    return true;
}

void readHeader(const Json& root, const Reader& r, Graph& graph)
{
    // The version first: a file of another version may legitimately have other keys.
    auto version = root.find("cloudgraph");
    if (version == root.end())
        r.fail("/cloudgraph", "not a CloudGraph graph: the format version \"cloudgraph\": " +
                                  std::to_string(Graph::kFormatVersion) + " is missing");
    if (!version->is_number_integer() || version->get<std::int64_t>() != Graph::kFormatVersion)
        r.fail("/cloudgraph", "unsupported format version " + version->dump() +
                                  " (this build reads version " +
                                  std::to_string(Graph::kFormatVersion) + ")");
    r.onlyKeys(root, "", {"cloudgraph", "description", "frames", "timeStep", "seed", "nodes"});

    if (auto d = root.find("description"); d != root.end()) {
        if (!d->is_string()) r.fail("/description", "the description must be a string");
        graph.description = d->get<std::string>();
    }
    if (auto f = root.find("frames"); f != root.end()) {
        r.object(*f, "/frames", "\"frames\"");
        r.onlyKeys(*f, "/frames", {"start", "end"});
        std::int64_t start = 0;
        std::int64_t end = 0;
        if (auto s = f->find("start"); s != f->end())
            start = r.integer(*s, "/frames/start", "start frame", 0, kMaxFrame);
        if (auto e = f->find("end"); e != f->end())
            end = r.integer(*e, "/frames/end", "end frame", 0, kMaxFrame);
        if (end < start)
            r.fail("/frames/end", "end frame " + std::to_string(end) +
                                      " is before the start frame " + std::to_string(start));
        graph.frames.start = static_cast<int>(start);
        graph.frames.end = static_cast<int>(end);
    }
    if (auto t = root.find("timeStep"); t != root.end()) {
        if (!t->is_number()) r.fail("/timeStep", "timeStep must be a number, got " + t->dump());
        const double dt = t->get<double>();
        if (!std::isfinite(dt) || dt <= 0 || dt > kMaxTimeStep)
            r.fail("/timeStep", "timeStep " + t->dump() + " must be > 0 and <= 86400 seconds");
        graph.timeStep = dt;
    }
    if (auto s = root.find("seed"); s != root.end()) {
        if (!s->is_number_unsigned())
            r.fail("/seed", "seed must be an integer >= 0, got " + s->dump());
        graph.seed = s->get<std::uint64_t>();
    }
}

/// A node's "position": two integers within +-kMaxPosition.
std::array<int, 2> readPosition(const Json& j, const std::string& ptr, const Reader& r)
{
    const auto inRange = [](const Json& v) {
        return v.is_number_integer() && std::llabs(v.get<std::int64_t>()) <= kMaxPosition;
    };
    if (!j.is_array() || j.size() != 2 || !inRange(j[0]) || !inRange(j[1]))
        r.fail(ptr + "/position", "\"position\" must be [x, y], two integers within +-" +
                                      std::to_string(kMaxPosition) + ", got " + j.dump());
    return {j[0].get<int>(), j[1].get<int>()};
}

GraphNode readNode(const std::string& id, const Json& j, const Reader& r, const Registry& registry,
                   const LoadOptions& options)
{
    const std::string ptr = "/nodes/" + jsonPointerToken(id);
    if (!validId(id))
        r.fail(printableText(ptr),
               "invalid node id '" + printableText(id) +
                   "': ids match [A-Za-z_][A-Za-z0-9_-]* and have at most 128 characters");
    r.object(j, ptr, "a node");
    r.onlyKeys(j, ptr, {"type", "params", "inputs", "comment", "bypass", "position"});

    auto type = j.find("type");
    if (type == j.end()) r.fail(ptr + "/type", "missing \"type\"");
    if (!type->is_string()) r.fail(ptr + "/type", "\"type\" must be a string");
    const std::string typeName = type->get<std::string>();
    const NodeDecl* decl = registry.findNode(typeName);
    if (!decl) {
        std::vector<std::string> types;
        for (const NodeDecl* d : registry.nodes()) types.push_back(d->type);
        r.fail(ptr + "/type", "unknown node type '" + typeName + "'" + didYouMean(typeName, types));
    }

    GraphNode node;
    node.id = id;
    node.decl = decl;
    node.params = ParamSet(&decl->params);
    node.pointer = ptr;

    if (auto b = j.find("bypass"); b != j.end()) {
        if (!b->is_boolean()) r.fail(ptr + "/bypass", "\"bypass\" must be true or false");
        node.bypass = b->get<bool>();
    }
    if (auto at = j.find("position"); at != j.end()) node.position = readPosition(*at, ptr, r);
    if (auto c = j.find("comment"); c != j.end()) {
        if (!c->is_string()) r.fail(ptr + "/comment", "\"comment\" must be a string");
        node.comment = c->get<std::string>();
    }
    if (auto params = j.find("params"); params != j.end()) {
        r.object(*params, ptr + "/params", "\"params\"");
        std::vector<std::string> names;
        for (const ParamDecl& p : decl->params) names.push_back(p.name);
        for (const auto& item : params->items()) {
            const std::string where = r.at(ptr + "/params/" + jsonPointerToken(item.key()));
            const ParamDecl* p = decl->findParam(item.key());
            if (!p) {
                throw InputError(where, "unknown parameter '" + item.key() + "' of " + typeName +
                                            didYouMean(item.key(), names));
            }
            ParamValue v = resolveInputFile(*p, paramFromJson(item.value(), *p, where), options);
            checkParamRole(*p, v, options, where);
            node.params.set(p->name, std::move(v));
        }
    }
    if (auto inputs = j.find("inputs"); inputs != j.end()) {
        r.object(*inputs, ptr + "/inputs", "\"inputs\"");
        std::vector<std::string> names;
        for (const PortDecl& p : decl->inputs) names.push_back(p.name);
        for (const auto& item : inputs->items()) {
            const std::string where = ptr + "/inputs/" + jsonPointerToken(item.key());
            if (!decl->findInput(item.key()))
                r.fail(where, "unknown input port '" + item.key() + "' of " + typeName +
                                  didYouMean(item.key(), names));
            const Json& v = item.value();
            const std::string text = v.is_string() ? v.get<std::string>() : std::string();
            const auto dot = text.find('.');
            if (!v.is_string() || dot == 0 || dot == std::string::npos || dot + 1 == text.size())
                r.fail(where, "an input must be a string \"node.port\", got " + v.dump());
            node.inputs[item.key()] = Connection{text.substr(0, dot), text.substr(dot + 1)};
        }
    }
    return node;
}

}  // namespace

Graph parseGraph(const std::string& text, const std::string& sourceName, const Registry& registry,
                 const LoadOptions& options)
{
    if (text.size() > options.maxFileBytes)
        throw InputError(sourceName, "graph is " + std::to_string(text.size()) +
                                         " bytes, over the limit of " +
                                         std::to_string(options.maxFileBytes) + " bytes");
    const Json root = parseJsonStrict(text, sourceName, options.maxJsonDepth);
    const Reader r{sourceName};
    if (!root.is_object()) {
        throw InputError(sourceName,
                         std::string("a graph must be a JSON object, got ") + root.type_name());
    }

    Graph graph;
    graph.limits = options;
    graph.setSourceName(sourceName);
    readHeader(root, r, graph);

    auto nodes = root.find("nodes");
    if (nodes == root.end()) r.fail("/nodes", "missing \"nodes\": a graph needs at least one node");
    r.object(*nodes, "/nodes", "\"nodes\"");
    if (nodes->empty() && options.requireComplete)
        r.fail("/nodes", "a graph needs at least one node");
    if (nodes->size() > kMaxNodes)
        r.fail("/nodes", std::to_string(nodes->size()) + " nodes, over the limit of " +
                             std::to_string(kMaxNodes));
    for (const auto& item : nodes->items()) {
        try {
            GraphNode node = readNode(item.key(), item.value(), r, registry, options);
            graph.validateNode(node);  // names the node itself
            graph.addNode(std::move(node));
        } catch (const InputError& e) {
            if (e.message().find("(node '") != std::string::npos) throw;
            throw InputError(e.where(), e.message() + " (node '" + item.key() + "')");
        }
    }
    graph.finalize();
    return graph;
}

std::string readGraphText(const std::filesystem::path& path, const LoadOptions& options)
{
    const std::string name = path.string();
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) throw InputError(name, "cannot read the graph file: " + ec.message());
    // Checked before reading, so a huge file is never pulled into memory.
    if (size > options.maxFileBytes)
        throw InputError(name, "file is " + std::to_string(size) + " bytes, over the limit of " +
                                   std::to_string(options.maxFileBytes) + " bytes");
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    if (in) text << in.rdbuf();
    if (!in || in.bad()) throw InputError(name, "cannot read the graph file");
    return text.str();
}

Graph parseGraphFile(const std::string& text, const std::filesystem::path& path,
                     const Registry& registry, const LoadOptions& options)
{
    LoadOptions besideTheGraph = options;
    besideTheGraph.inputFileBase = path.parent_path();
    Graph graph = parseGraph(text, path.string(), registry, besideTheGraph);
    graph.source = path;
    return graph;
}

Graph loadGraph(const std::filesystem::path& path, const Registry& registry,
                const LoadOptions& options)
{
    return parseGraphFile(readGraphText(path, options), path, registry, options);
}

void applySetOverride(Graph& graph, const std::string& assignment)
{
    const auto eq = assignment.find('=');
    const std::string lhs = assignment.substr(0, eq);
    const std::string where = "--set " + lhs;
    const auto dot = lhs.find('.');
    if (eq == std::string::npos || dot == std::string::npos || dot == 0 || dot + 1 == lhs.size())
        throw InputError(where, "expected node.param=value, got '" + assignment + "'");
    const std::string valueText = assignment.substr(eq + 1);
    // JSON if it parses (numbers, true, [1,2], "quoted"), else the text itself as a string.
    Json value = Json::parse(valueText, nullptr, false);
    if (value.is_discarded()) value = valueText;
    // A relative input file on the command line is relative to the working directory, not
    // to the graph file as the graph's own values are.
    const GraphNode* node = graph.find(lhs.substr(0, dot));
    const ParamDecl* decl = node ? node->decl->findParam(lhs.substr(dot + 1)) : nullptr;
    // "bypass" is the node's own switch, unless its type has a parameter of that name.
    if (!decl && lhs.substr(dot + 1) == "bypass") {
        if (!value.is_boolean()) throw InputError(where, "bypass must be true or false");
        graph.setBypass(lhs.substr(0, dot), value.get<bool>(), where);
        return;
    }
    if (decl && decl->role == ParamRole::InputFile && value.is_string() &&
        !value.get<std::string>().empty())
        value = std::filesystem::absolute(value.get<std::string>()).lexically_normal().string();
    graph.setParam(lhs.substr(0, dot), lhs.substr(dot + 1), value, where);
}

Json graphToJson(const Graph& graph)
{
    Json out = Json::object();
    out["cloudgraph"] = Graph::kFormatVersion;
    if (!graph.description.empty()) out["description"] = graph.description;
    out["frames"] = {{"start", graph.frames.start}, {"end", graph.frames.end}};
    out["timeStep"] = graph.timeStep;
    out["seed"] = graph.seed;
    Json nodes = Json::object();
    for (const GraphNode& node : graph.nodes()) {
        Json n = Json::object();
        n["type"] = node.decl->type;
        Json params = Json::object();
        for (std::size_t i = 0; i < node.decl->params.size(); ++i) {
            const ParamDecl& p = node.decl->params[i];
            const ParamValue& v = node.params.valueAt(i);
            if (v == p.defaultValue) continue;
            const auto* file = std::get_if<std::string>(&v);
            params[p.name] = file && p.role == ParamRole::InputFile
                                 ? Json(inputFileInGraph(*file, graph.limits.inputFileBase))
                                 : paramToJson(v);
        }
        if (!params.empty()) n["params"] = std::move(params);
        Json inputs = Json::object();
        for (const auto& [port, conn] : node.inputs) inputs[port] = conn.node + "." + conn.port;
        if (!inputs.empty()) n["inputs"] = std::move(inputs);
        if (!node.comment.empty()) n["comment"] = node.comment;
        if (node.bypass) n["bypass"] = true;
        if (node.position) n["position"] = {(*node.position)[0], (*node.position)[1]};
        nodes[node.id] = std::move(n);
    }
    out["nodes"] = std::move(nodes);
    return out;
}

}  // namespace cg
