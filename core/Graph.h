#pragma once
/// A loaded, validated graph: node instances with their parameters and wiring.
/// Editing goes through setParam(), which validates like loading does.

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/NodeDecl.h"
#include "core/Param.h"
#include "util/SystemMemory.h"

namespace cg {

class Registry;

struct Connection {
    std::string node;  ///< upstream node id
    std::string port;  ///< upstream output port
};

struct GraphNode {
    std::string id;
    const NodeDecl* decl = nullptr;
    ParamSet params;
    std::map<std::string, Connection> inputs;  ///< by input port name
    std::string pointer;                       ///< JSON pointer of the node, "/nodes/<id>"
    std::string comment;                       ///< free text from the file, kept on save
    /// "bypass": true. A writer writes nothing (its file list is empty); any other node passes
    /// its first input through as each of its outputs, which must be of that input's type.
    bool bypass = false;
    /// "position": [x, y], where the network editor of `serve` draws the node (page pixels,
    /// integers); absent, the editor lays it out by depth. Kept on save, never cooked.
    std::optional<std::array<int, 2>> position;
};

struct FrameRange {
    int start = 0;
    int end = 0;  ///< inclusive
};

/// Limits applied while loading untrusted graphs.
struct LoadOptions {
    /// The most one node may allocate: util::nodeAllocationLimitBytes() (a quarter of the
    /// machine's memory, at most 16 GiB).
    std::uint64_t allocationLimitBytes = util::nodeAllocationLimitBytes();
    int maxJsonDepth = 64;
    std::size_t maxFileBytes = 64u << 20;
    /// Lets OutputPath parameters be absolute or climb out with "..".
    bool allowPathsOutsideOut = false;
    /// Lets a graph set Program parameters (--allow-graph-programs): the user trusts it.
    bool allowGraphPrograms = false;
    /// Refuses a graph that cannot cook yet: one without nodes, or with a required input not
    /// connected. The Python API turns it off while a graph is built node by node, and
    /// checks again before it cooks or saves.
    bool requireComplete = true;
    /// Where a relative input file (ParamRole::InputFile) is found: loadGraph sets the graph
    /// file's directory, so a graph and the files beside it move together, as a Houdini or
    /// Blender scene's relative paths do. Empty: the working directory.
    std::filesystem::path inputFileBase;
};

class Graph {
public:
    static constexpr int kFormatVersion = 1;

    std::filesystem::path source;  ///< file it was loaded from, if any
    FrameRange frames;             ///< the animation; simulations start at frames.start
    double timeStep = 1.0;         ///< seconds per frame
    std::uint64_t seed = 0;
    std::string description;
    LoadOptions limits;

    /// Prefix of error locations ("graph.json"); errors read "graph.json:/nodes/a: ...".
    const std::string& sourceName() const { return mSourceName; }
    void setSourceName(std::string name) { mSourceName = std::move(name); }

    const std::vector<GraphNode>& nodes() const { return mNodes; }
    const GraphNode* find(const std::string& id) const;
    std::size_t indexOf(const std::string& id) const;  ///< throws std::out_of_range
    /// Node indices, every node after all of its inputs (ties broken by id).
    const std::vector<std::size_t>& topologicalOrder() const { return mOrder; }
    /// For each node, the indices of its upstream nodes (deduplicated, sorted).
    const std::vector<std::vector<std::size_t>>& upstream() const { return mUpstream; }
    /// Nodes that feed no other node.
    std::vector<std::size_t> sinks() const;

    /// Validates `value` against the parameter's declaration and the node's cross-checks,
    /// then sets it. Throws InputError naming `where` (e.g. "--set a.b" or a JSON pointer).
    void setParam(const std::string& nodeId, const std::string& param, const nlohmann::json& value,
                  const std::string& where = "");

    /// Bypasses a node or stops bypassing it (`--set node.bypass=true`), checked as loading
    /// checks "bypass". Throws InputError naming `where`.
    void setBypass(const std::string& nodeId, bool bypass, const std::string& where = "");

    // Used by the loader.
    void addNode(GraphNode node);
    /// Checks wiring (ports exist, types match, required inputs present), rejects cycles,
    /// and computes the topological order. Throws InputError with JSON pointers.
    void finalize();
    /// Runs every node's NodeDecl::validate. Throws InputError.
    void validateNode(const GraphNode& node) const;
    /// Refuses a bypass the node cannot do (see GraphNode::bypass).
    void checkBypass(const GraphNode& node) const;
    /// Refuses an output file name without #### that the node writes on several frames.
    void checkFramesNumbered(const GraphNode& node) const;

    /// `pointer` prefixed by the source name, as errors name places ("g.json:/nodes/a").
    std::string locate(const std::string& pointer) const;

private:
    /// The node `nodeId`, to edit; InputError naming `where` (or /nodes) with the ids there are.
    GraphNode& nodeToEdit(const std::string& nodeId, const std::string& where);

    std::string mSourceName;
    std::vector<GraphNode> mNodes;  ///< sorted by id after finalize()
    bool mSorted = true;            ///< mNodes is sorted by id (binary search works)
    std::vector<std::size_t> mOrder;
    std::vector<std::vector<std::size_t>> mUpstream;
};

/// A relative InputFile value names a file beside the graph: options.inputFileBase / value
/// (a value of another role, or an absolute one, is returned as it is).
ParamValue resolveInputFile(const ParamDecl& decl, ParamValue value, const LoadOptions& options);
/// The inverse, for writing a graph back: a resolved input file as the graph file names it,
/// relative to `base` (absolute where it lies outside an absolute `base`).
std::string inputFileInGraph(const std::string& resolved, const std::filesystem::path& base);

/// Checks what paramFromJson cannot see: an OutputPath value must be a relative path with
/// no ".." component unless options.allowPathsOutsideOut. Throws InputError naming `where`.
void checkParamRole(const ParamDecl& decl, const ParamValue& value, const LoadOptions& options,
                    const std::string& where);

/// Loads and validates a graph file. Throws InputError naming the file and a JSON pointer
/// or byte offset; nothing is cooked.
Graph loadGraph(const std::filesystem::path& path, const Registry& registry,
                const LoadOptions& options = {});
/// A graph file's text, refused (InputError naming the file) when it cannot be read or is
/// over options.maxFileBytes, checked before it is read.
std::string readGraphText(const std::filesystem::path& path, const LoadOptions& options);
/// loadGraph once the text is read: relative input files are found beside `path`.
Graph parseGraphFile(const std::string& text, const std::filesystem::path& path,
                     const Registry& registry, const LoadOptions& options);
/// Same, from text; `sourceName` is used in messages.
Graph parseGraph(const std::string& text, const std::string& sourceName, const Registry& registry,
                 const LoadOptions& options = {});
/// Applies a command-line override "node.param=value"; the value is JSON, or a bare string.
void applySetOverride(Graph& graph, const std::string& assignment);
/// The graph back as JSON (format version, frames, nodes with every non-default parameter).
nlohmann::json graphToJson(const Graph& graph);

}  // namespace cg
