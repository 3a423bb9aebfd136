#pragma once
/// Cooks a graph for frames: content keys, cache lookups (memory, then disk), parallel
/// branches, simulations stepped from their previous frame, and a record of every cook.
///
/// Keys: a node's key hashes its type and version, its parameters, the keys of its inputs,
/// the context values it reads (time step, seed) and, for frame-dependent nodes, the frame.
/// A simulation's key at frame N also hashes its key at N-1, so it names the whole history.
/// A node none of whose upstream depends on the frame has one key for the whole animation.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/CookHistory.h"
#include "core/DiskCache.h"
#include "core/EvalContext.h"
#include "core/Graph.h"
#include "core/MemoryCache.h"
#include "core/Registry.h"
#include "core/RunReport.h"

namespace cg {

struct Progress {
    std::size_t done = 0;   ///< node-frames finished
    std::size_t total = 0;  ///< node-frames this run will visit
    int frame = 0;
    std::string node;  ///< the node whose frame just finished (cooked or from a cache)
};

struct EvaluatorOptions {
    std::size_t memoryBudgetBytes = std::size_t(4) << 30;
    std::shared_ptr<DiskCache> diskCache;  ///< optional
    std::filesystem::path outDir = ".";
    std::shared_ptr<CancelToken> cancel = std::make_shared<CancelToken>();
    std::function<void(const Progress&)> onProgress;  ///< called from worker threads
};

class Evaluator {
public:
    /// Outputs of every cooked node at one frame, by node index (nullptr if not needed).
    using FrameOutputs = std::vector<OutputsPtr>;
    using FrameCallback = std::function<void(int frame, const FrameOutputs&)>;

    Evaluator(const Registry& registry, EvaluatorOptions options);

    /// Cooks `targets` (node ids; empty = the graph's sinks) and everything they need, for
    /// frames first..last in order. Throws InputError/CookError/Cancelled; whatever failed
    /// or was cancelled is not cached.
    void cookFrames(const Graph& graph, int first, int last,
                    const std::vector<std::string>& targets = {},
                    const FrameCallback& onFrame = {});
    /// Cooks one node at one frame and returns its outputs.
    OutputsPtr pull(const Graph& graph, const std::string& nodeId, int frame);
    /// The content key of a node's output at a frame, without cooking anything.
    Key key(const Graph& graph, const std::string& nodeId, int frame);

    RunReport& report() { return mReport; }
    /// Replaces the token later cooks watch: a token once cancelled stays so, and a caller
    /// that cooks again (the Python API) gives each cook a fresh one.
    void setCancelToken(std::shared_ptr<CancelToken> token) { mOptions.cancel = std::move(token); }
    MemoryCache& memoryCache() { return mMemory; }
    const EvaluatorOptions& options() const { return mOptions; }

private:
    class Session;
    friend class Session;

    const Registry& mRegistry;
    EvaluatorOptions mOptions;
    MemoryCache mMemory;
    RunReport mReport;
    CookHistory mHistory;
};

}  // namespace cg
