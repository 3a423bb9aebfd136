#include "core/Graph.h"

#include <algorithm>
#include <functional>
#include <queue>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "core/Error.h"
#include "core/JsonParse.h"
#include "util/FramePattern.h"
#include "util/InputFile.h"

namespace cg {

ParamValue resolveInputFile(const ParamDecl& decl, ParamValue value, const LoadOptions& options)
{
    const auto* file = std::get_if<std::string>(&value);
    if (!file || decl.role != ParamRole::InputFile || file->empty() ||
        std::filesystem::path(*file).is_absolute() || options.inputFileBase.empty())
        return value;
    return (options.inputFileBase / *file).lexically_normal().string();
}

std::string inputFileInGraph(const std::string& resolved, const std::filesystem::path& base)
{
    const std::filesystem::path file(resolved);
    if (base.empty() || resolved.empty() || file.is_absolute() != base.is_absolute())
        return resolved;
    const std::filesystem::path relative = file.lexically_relative(base.lexically_normal());
    if (relative.empty() || (file.is_absolute() && *relative.begin() == "..")) return resolved;
    return relative.string();
}

void checkParamRole(const ParamDecl& decl, const ParamValue& value, const LoadOptions& options,
                    const std::string& where)
{
    if (decl.role == ParamRole::Program && !options.allowGraphPrograms &&
        value != decl.defaultValue) {
        throw InputError(where, "a graph may not name a program to run (" + paramToString(value) +
                                    "); the program is found on PATH by its name '" +
                                    paramToString(decl.defaultValue) +
                                    "' or given by the environment (see the node's docs); "
                                    "pass --allow-graph-programs to trust this graph");
    }
    if (decl.role == ParamRole::InputFile) {
        // Checked when the graph is loaded, so `validate` refuses what `run` could not read.
        const auto* file = std::get_if<std::string>(&value);
        if (!file) return;
        if (const std::string problem = util::inputFileProblem(*file, options.allocationLimitBytes);
            !problem.empty())
            throw InputError(where, "input file '" + *file + "' " + problem);
        return;
    }
    if (decl.role != ParamRole::OutputPath) return;
    const auto* path = std::get_if<std::string>(&value);
    if (!path) return;
    if (const std::string problem = util::outputFileProblem(*path); !problem.empty())
        throw InputError(where, "bad output file: " + problem);
    if (options.allowPathsOutsideOut) return;
    bool escapes = (*path)[0] == '/';
    // Split by hand: std::filesystem would also accept "a/../.." after normalising.
    std::size_t start = 0;
    while (!escapes && start <= path->size()) {
        std::size_t end = path->find('/', start);
        if (end == std::string::npos) end = path->size();
        escapes = path->compare(start, end - start, "..") == 0;
        start = end + 1;
    }
    if (escapes) {
        throw InputError(where, "output path '" + *path +
                                    "' escapes the output directory "
                                    "(use --allow-outside-out to permit)");
    }
}

std::string Graph::locate(const std::string& pointer) const
{
    return mSourceName.empty() ? pointer : mSourceName + ":" + pointer;
}

const GraphNode* Graph::find(const std::string& id) const
{
    if (mSorted) {
        auto it =
            std::lower_bound(mNodes.begin(), mNodes.end(), id,
                             [](const GraphNode& n, const std::string& k) { return n.id < k; });
        return it != mNodes.end() && it->id == id ? &*it : nullptr;
    }
    for (const GraphNode& n : mNodes)
        if (n.id == id) return &n;
    return nullptr;
}

std::size_t Graph::indexOf(const std::string& id) const
{
    const GraphNode* n = find(id);
    if (!n) throw std::out_of_range("no node '" + id + "'");
    return static_cast<std::size_t>(n - mNodes.data());
}

std::vector<std::size_t> Graph::sinks() const
{
    std::vector<bool> feeds(mNodes.size(), false);
    for (const auto& ups : mUpstream)
        for (std::size_t u : ups) feeds[u] = true;
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < mNodes.size(); ++i)
        if (!feeds[i]) out.push_back(i);
    return out;
}

void Graph::addNode(GraphNode node)
{
    if (node.pointer.empty()) node.pointer = "/nodes/" + jsonPointerToken(node.id);
    if (find(node.id))
        throw InputError(locate(node.pointer), "duplicate node id '" + node.id + "'");
    if (!mNodes.empty() && mNodes.back().id >= node.id) mSorted = false;
    mNodes.push_back(std::move(node));
    mOrder.clear();
    mUpstream.clear();
}

void Graph::validateNode(const GraphNode& node) const
{
    checkBypass(node);
    checkFramesNumbered(node);
    if (!node.decl->validate) return;
    const ParamChecker checker{locate(node.pointer), limits.allocationLimitBytes};
    try {
        node.decl->validate(node.params, checker);
    } catch (const InputError& e) {
        // ParamChecker names the parameter; the message also names the node.
        throw InputError(e.where(), e.message() + " (node '" + node.id + "')");
    }
}

void Graph::checkBypass(const GraphNode& node) const
{
    if (!node.bypass) return;
    const NodeDecl& d = *node.decl;
    const std::string where = locate(node.pointer + "/bypass");
    const std::string what = "'" + node.id + "' (" + d.type + ")";
    if (d.writesFiles) {
        for (const PortDecl& out : d.outputs)
            if (out.type != "Text")
                throw InputError(where, what + " cannot be bypassed: its output '" + out.name +
                                            "' is " + out.type + ", not a file list");
        return;
    }
    if (d.inputs.empty())
        throw InputError(where, what +
                                    " has no input to pass through: bypass is for writers and "
                                    "for nodes whose outputs are of their first input's type");
    const PortDecl& first = d.inputs.front();
    for (const PortDecl& out : d.outputs)
        if (out.type != first.type)
            throw InputError(where, what + " makes " + out.type + " ('" + out.name + "') from " +
                                        first.type + " ('" + first.name +
                                        "'): a bypassed node passes its first input through, so "
                                        "it cannot stand in for '" +
                                        out.name +
                                        "'; bypass a writer or a node whose outputs "
                                        "are of its first input's type");
    if (!node.inputs.count(first.name))
        throw InputError(where, what + ": its input '" + first.name +
                                    "' is not connected, so there is nothing to pass through");
}

GraphNode& Graph::nodeToEdit(const std::string& nodeId, const std::string& where)
{
    const GraphNode* found = find(nodeId);
    if (!found) {
        std::vector<std::string> ids;
        for (const GraphNode& n : mNodes) ids.push_back(n.id);
        throw InputError(where.empty() ? locate("/nodes") : where,
                         "unknown node '" + nodeId + "'" + didYouMean(nodeId, ids));
    }
    return mNodes[static_cast<std::size_t>(found - mNodes.data())];
}

void Graph::setBypass(const std::string& nodeId, bool bypass, const std::string& where)
{
    GraphNode& node = nodeToEdit(nodeId, where);
    GraphNode trial = node;
    trial.bypass = bypass;
    try {
        validateNode(trial);
    } catch (const InputError& e) {
        if (where.empty()) throw;
        throw InputError(where, e.message());
    }
    node.bypass = bypass;
}

void Graph::checkFramesNumbered(const GraphNode& node) const
{
    if (!node.decl->framesWritten || node.bypass) return;
    for (std::size_t i = 0; i < node.decl->params.size(); ++i) {
        const ParamDecl& decl = node.decl->params[i];
        if (decl.role != ParamRole::OutputPath) continue;
        const auto* file = std::get_if<std::string>(&node.params.valueAt(i));
        if (!file || util::firstHashRun(std::filesystem::path(*file).filename().string())) continue;
        if (node.decl->framesWritten(node.params, frames.start, frames.end) < 2) continue;
        throw InputError(locate(node.pointer + "/params/" + decl.name),
                         "'" + *file + "' has no #### frame number, but the node writes it " +
                             "on several frames of " + std::to_string(frames.start) + ".." +
                             std::to_string(frames.end) +
                             ": each would overwrite the last; put #### in the file name (it "
                             "becomes the frame) or write one frame ('every') (node '" +
                             node.id + "')");
    }
}

void Graph::setParam(const std::string& nodeId, const std::string& param,
                     const nlohmann::json& value, const std::string& where)
{
    GraphNode& node = nodeToEdit(nodeId, where);
    const std::string place =
        where.empty() ? locate(node.pointer + "/params/" + jsonPointerToken(param)) : where;
    const std::string inNode = " (node '" + nodeId + "')";
    const ParamDecl* decl = node.decl->findParam(param);
    if (!decl) {
        std::vector<std::string> names;
        for (const ParamDecl& p : node.decl->params) names.push_back(p.name);
        throw InputError(place,
                         "unknown parameter '" + param + "'" + didYouMean(param, names) + inNode);
    }
    ParamValue v;
    try {
        v = resolveInputFile(*decl, paramFromJson(value, *decl, place), limits);
        checkParamRole(*decl, v, limits, place);
    } catch (const InputError& e) {
        throw InputError(e.where(), e.message() + inNode);
    }
    // Validate a copy so a refused value leaves the graph as it was.
    GraphNode trial = node;
    trial.params.set(param, v);
    try {
        validateNode(trial);
    } catch (const InputError& e) {
        if (where.empty()) throw;
        throw InputError(where, e.message());
    }
    node.params = std::move(trial.params);
}

void Graph::finalize()
{
    std::sort(mNodes.begin(), mNodes.end(),
              [](const GraphNode& a, const GraphNode& b) { return a.id < b.id; });
    mSorted = true;
    const std::size_t n = mNodes.size();
    mUpstream.assign(n, {});
    mOrder.clear();

    for (std::size_t i = 0; i < n; ++i) {
        const GraphNode& node = mNodes[i];
        const NodeDecl& decl = *node.decl;
        const std::string inNode = " of node '" + node.id + "'";
        for (const auto& [portName, conn] : node.inputs) {
            const std::string where =
                locate(node.pointer + "/inputs/" + jsonPointerToken(portName));
            const PortDecl* in = decl.findInput(portName);
            if (!in) {
                std::vector<std::string> names;
                for (const PortDecl& p : decl.inputs) names.push_back(p.name);
                throw InputError(where, "unknown input port '" + portName + "'" + inNode + " (" +
                                            decl.type + ")" + didYouMean(portName, names));
            }
            const GraphNode* up = find(conn.node);
            if (!up) {
                throw InputError(where, "input '" + portName + "'" + inNode + " is wired to '" +
                                            conn.node + "." + conn.port +
                                            "', but there is no node '" + conn.node + "'");
            }
            const PortDecl* out = up->decl->findOutput(conn.port);
            if (!out) {
                std::string names;
                for (const PortDecl& p : up->decl->outputs)
                    names += (names.empty() ? "" : ", ") + p.name;
                throw InputError(where, "node '" + conn.node + "' (" + up->decl->type +
                                            ") has no output port '" + conn.port +
                                            "'; its outputs are: " + names + " (input '" +
                                            portName + "'" + inNode + ")");
            }
            if (out->type != in->type) {
                throw InputError(where, "input '" + portName + "'" + inNode + " takes " + in->type +
                                            ", but '" + conn.node + "." + conn.port + "' gives " +
                                            out->type);
            }
            mUpstream[i].push_back(static_cast<std::size_t>(up - mNodes.data()));
        }
        for (const PortDecl& in : decl.inputs) {
            if (!in.optional && limits.requireComplete && !node.inputs.count(in.name)) {
                throw InputError(locate(node.pointer + "/inputs/" + jsonPointerToken(in.name)),
                                 "required input '" + in.name + "'" + inNode + " (" + decl.type +
                                     ") is not connected");
            }
        }
        auto& ups = mUpstream[i];
        std::sort(ups.begin(), ups.end());
        ups.erase(std::unique(ups.begin(), ups.end()), ups.end());
    }

    // Kahn's algorithm; the smallest ready index (= id) goes first, so the order is stable.
    std::vector<std::vector<std::size_t>> downstream(n);
    std::vector<std::size_t> pending(n);
    for (std::size_t i = 0; i < n; ++i) {
        pending[i] = mUpstream[i].size();
        for (std::size_t u : mUpstream[i]) downstream[u].push_back(i);
    }
    std::priority_queue<std::size_t, std::vector<std::size_t>, std::greater<>> ready;
    for (std::size_t i = 0; i < n; ++i)
        if (pending[i] == 0) ready.push(i);
    while (!ready.empty()) {
        const std::size_t i = ready.top();
        ready.pop();
        mOrder.push_back(i);
        for (std::size_t d : downstream[i])
            if (--pending[d] == 0) ready.push(d);
    }
    if (mOrder.size() == n) return;

    // Every node left has an upstream node that is also left, so walking upstream from the
    // smallest one must revisit a node: that loop is a cycle.
    std::size_t at = 0;
    while (pending[at] == 0) ++at;
    std::vector<std::size_t> walk;
    std::vector<std::size_t> seenAt(n, n);
    while (seenAt[at] == n) {
        seenAt[at] = walk.size();
        walk.push_back(at);
        for (std::size_t u : mUpstream[at]) {
            if (pending[u] != 0) {
                at = u;
                break;
            }
        }
    }
    std::vector<std::size_t> cycle(walk.begin() + static_cast<std::ptrdiff_t>(seenAt[at]),
                                   walk.end());
    std::reverse(cycle.begin(), cycle.end());  // upstream walk -> data-flow direction
    std::rotate(cycle.begin(), std::min_element(cycle.begin(), cycle.end()), cycle.end());
    std::string text;
    for (std::size_t c : cycle) text += mNodes[c].id + " -> ";
    text += mNodes[cycle.front()].id;
    const std::string where = locate(mNodes[cycle.front()].pointer);
    mOrder.clear();
    mUpstream.clear();
    throw InputError(where, "cycle: " + text);
}

}  // namespace cg
