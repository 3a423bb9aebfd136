#pragma once
/// A graph being edited: its document, validated on every edit by the same loader as the
/// CLI's, and the evaluators that cook it (one per cache and output directory, kept between
/// cooks so that a second cook reuses what the first made and recooks only what an edit
/// dirtied). The Python module's Graph and `cloudgraph serve` both edit through it.

#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/Data.h"
#include "core/EvalContext.h"
#include "core/Evaluator.h"
#include "core/Graph.h"

namespace cg {

class Registry;

/// loadGraph could not read the file at all (missing, unreadable): the error names the file
/// alone, with no place in it.
class UnreadableGraph : public InputError {
public:
    using InputError::InputError;
};

/// cook() was called while another cook of the same document was under way.
class CookInProgress : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Where the cook under way stands (GraphDocument::progress), for a page that polls it.
struct CookProgress {
    bool cooking = false;
    std::size_t done = 0;   ///< node-frames finished, cooked or from a cache
    std::size_t total = 0;  ///< node-frames this cook visits (grows as it finds what it needs)
    double seconds = 0;     ///< since the cook began
    std::vector<std::string> finished;  ///< the nodes done (once each), in the order they finished
};

class GraphDocument {
public:
    /// Loads a graph file (errors name the file and JSON pointer, as the CLI's do). A graph
    /// being built may still lack nodes or wires: cook and save check it whole.
    static std::unique_ptr<GraphDocument> load(const std::filesystem::path& path,
                                               const Registry& registry,
                                               const LoadOptions& options = {});
    /// A graph from JSON text; `name` prefixes error locations, relative input files are
    /// found under `baseDir`.
    static std::unique_ptr<GraphDocument> parse(const std::string& text, const std::string& name,
                                                const std::string& baseDir,
                                                const Registry& registry);

    const Graph& graph() const { return mGraph; }
    /// The graph as JSON (graphToJson: every non-default parameter).
    nlohmann::json json() const;
    std::string toJson() const;
    /// Sets one parameter, checked as loading checks it; on an error nothing changes.
    void setParam(const std::string& node, const std::string& param, const nlohmann::json& value);
    /// Applies a command line's `--set node.param=value` (applySetOverride's checks).
    void applySetOverride(const std::string& assignment);
    /// Replaces the whole graph by `text` (an edited toJson()): loaded like a file except
    /// that required inputs may still be unconnected; on an error the graph stays as it was.
    void replace(const std::string& text);
    /// The same for the graph file's new text (changed on disk by a text editor): its layout
    /// is the one save() keeps from now on.
    void reload(const std::string& fileText);
    /// The graph as the CLI would load it: complete, or an InputError. Kept until the next
    /// edit, so that cooking again checks nothing twice.
    const Graph& completeGraph() const;
    /// Writes the graph to `path` atomically, after checking the graph is complete, in the
    /// layout of the file it was loaded from (graphFileText: its key order and spelling, so
    /// a diff shows the edit); returns the bytes written. A symbolic link is written through
    /// to its target, whose mode and owner are kept (util::saveFileAtomically).
    std::string save(const std::filesystem::path& path);
    /// The file's text as last loaded, reloaded or saved (empty for a parsed document).
    const std::string& fileText() const { return mLayout; }

    /// Cooks output `port` of `node` at `frame` and what it needs, in `graph`: a copy of
    /// completeGraph() taken earlier, so that edits may go on meanwhile. `cache` (may be
    /// empty) is a disk cache directory shared with the CLI, `out` where writer nodes write.
    /// `alsoCook` names more nodes to cook at the frame (writers, say), in the same cook and
    /// report. One cook at a time: a second one throws CookInProgress while the first runs.
    /// cancel() from another thread stops it (Cancelled): nothing partial is cached. Whatever
    /// it throws (a `cache` that cannot be made: InputError), the cook is over: the next
    /// one may start.
    DataPtr cook(const Graph& graph, const std::string& node, const std::string& port, int frame,
                 const std::string& cache, const std::string& out,
                 const std::vector<std::string>& alsoCook = {});
    /// Cancels the cook under way, if any.
    void cancel();
    /// The cook under way's progress (cooking false: the last cook's, when it ended).
    CookProgress progress() const;
    /// The last cook's run report (JSON): what cooked or came from a cache, and why.
    std::string lastReport() const;

private:
    GraphDocument(Graph graph, const Registry& registry);
    Evaluator& evaluatorFor(const std::string& cache, const std::string& out);
    /// Marks the cook over and keeps its report (`evaluator` null: none was made).
    void endCook(Evaluator* evaluator) noexcept;

    Graph mGraph;                            ///< loaded with requireComplete off
    mutable std::optional<Graph> mComplete;  ///< completeGraph() until the next edit
    std::string mLayout;  ///< the file's text as last loaded or saved: what save() keeps
    const Registry& mRegistry;
    std::map<std::pair<std::string, std::string>, std::unique_ptr<Evaluator>> mEvaluators;
    mutable std::mutex mCookMutex;         ///< guards mCancel, mLastReport and mProgress
    std::shared_ptr<CancelToken> mCancel;  ///< the cook under way's token
    std::string mLastReport = "{}";
    CookProgress mProgress;
    std::chrono::steady_clock::time_point mCookStart;
};

}  // namespace cg
