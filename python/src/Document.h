#pragma once
/// The graph behind a Python `cloudgraph.Graph`: its JSON document, validated on every edit
/// by the same loader as the CLI's, and the evaluators that cook it (one per cache and
/// output directory, kept between cooks so a second cook reuses what the first made).

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

#include <pybind11/pybind11.h>

#include "core/EvalContext.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Registry.h"

namespace cg::python {

/// Every node type the module knows: the built-in nodes and the plugins of
/// CLOUDGRAPH_PLUGIN_PATH, as the CLI has them, and the Python nodes registered since; or,
/// inside the CLI, the CLI's registry (setSharedRegistry).
Registry& sharedRegistry();
/// Makes `registry` the one sharedRegistry() returns (the CLI's, for --python-nodes).
void setSharedRegistry(Registry* registry);

class Document {
public:
    /// Loads a graph file (errors name the file and JSON pointer, as the CLI's do).
    static std::unique_ptr<Document> load(const std::string& path);
    /// A graph from JSON text; `name` prefixes error locations, relative input files are
    /// found under `baseDir`.
    static std::unique_ptr<Document> parse(const std::string& text, const std::string& name,
                                           const std::string& baseDir);

    /// The graph as JSON text (graphToJson: every non-default parameter).
    std::string toJson() const;
    /// Sets one parameter from its JSON text, checked as loading checks it.
    void setParam(const std::string& node, const std::string& param, const std::string& valueJson);
    /// Replaces the whole graph by `text` (an edited toJson()): loaded like a file except that
    /// required inputs may still be unconnected; on an error the graph stays as it was.
    void replace(const std::string& text);
    /// Writes toJson() to `path` atomically, after checking the graph is complete.
    void save(const std::string& path) const;

    /// Cooks output `port` of `node` at `frame` with the GIL released, and converts it to a
    /// Python value. `cache` (may be empty) is a disk cache directory shared with the CLI,
    /// `out` where writer nodes write. Ctrl-C, or cancel() from another thread, cancels it:
    /// nothing partial is cached.
    pybind11::object cook(const std::string& node, const std::string& port, int frame,
                          const std::string& cache, const std::string& out);
    /// Cancels the cook under way, if any.
    void cancel();
    /// The last cook's run report (JSON text): what cooked or came from a cache, and why.
    std::string lastReport() const { return mLastReport; }

    int firstFrame() const { return mGraph.frames.start; }
    int lastFrame() const { return mGraph.frames.end; }

private:
    explicit Document(Graph graph);
    /// The graph as the CLI would load it: complete, or an InputError.
    Graph completeGraph() const;
    Evaluator& evaluatorFor(const std::string& cache, const std::string& out);

    Graph mGraph;  ///< loaded with requireComplete off
    std::map<std::pair<std::string, std::string>, std::unique_ptr<Evaluator>> mEvaluators;
    std::mutex mCancelMutex;
    std::shared_ptr<CancelToken> mCancel;  ///< the cook under way's token
    std::string mLastReport = "{}";
};

}  // namespace cg::python
