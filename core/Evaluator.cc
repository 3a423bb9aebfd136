#include "core/Evaluator.h"

#include <algorithm>
#include <chrono>
#include <climits>
#include <set>
#include <stdexcept>
#include <unordered_map>
#include <variant>

#include <spdlog/spdlog.h>

#include "core/CoreData.h"
#include "core/Error.h"
#include "core/FramePipeline.h"
#include "core/Hash.h"
#include "core/WrittenFiles.h"
#include "util/AtomicFile.h"

namespace cg {

namespace {

constexpr int kAnyFrame = INT_MIN;  // memo slot of a node whose output ignores the frame
/// Frames cooked at once (FramePipeline): one frame's writers overlap the next frame's cooks.
constexpr int kFramesInFlight = 2;

double secondsSince(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Numbers and short texts among a node's outputs, for the run report.
nlohmann::json smallValues(const OutputMap& outputs)
{
    constexpr std::size_t kShortText = 256;
    nlohmann::json values = nlohmann::json::object();
    for (const auto& [port, value] : outputs) {
        if (const auto* f = dynamic_cast<const FloatData*>(value.get())) {
            values[port] = f->value;
        } else if (const auto* i = dynamic_cast<const IntData*>(value.get())) {
            values[port] = i->value;
        } else if (const auto* t = dynamic_cast<const TextData*>(value.get());
                   t && !t->value.empty() && t->value.size() <= kShortText) {
            values[port] = t->value;
        }
    }
    return values;
}

}  // namespace

/// The state of one cookFrames() call: key memo, simulation states in flight, progress.
class Evaluator::Session {
public:
    Session(Evaluator& ev, const Graph& graph)
        : mEv(ev), mGraph(graph), mWritten(ev.mOptions.diskCache, ev.mOptions.outDir)
    {
        const auto& nodes = graph.nodes();
        const std::size_t n = nodes.size();
        mKeys.resize(n);
        mTimeVarying.assign(n, false);
        mOrderIndex.assign(n, 0);
        mHeld.resize(n);
        mHeldMutex = std::vector<std::mutex>(n);
        const auto& order = graph.topologicalOrder();
        for (std::size_t i = 0; i < order.size(); ++i) {
            const std::size_t idx = order[i];
            mOrderIndex[idx] = i;
            bool varying =
                dependsOnFrame(*nodes[idx].decl, nodes[idx].params) || nodes[idx].decl->simulation;
            for (std::size_t up : graph.upstream()[idx]) varying = varying || mTimeVarying[up];
            mTimeVarying[idx] = varying;
        }
        // Disk records are per graph file and node id, so two graphs don't explain each other.
        Hasher h;
        h.str(graph.source.empty()
                  ? std::string("<memory>")
                  : std::filesystem::absolute(graph.source).lexically_normal().string());
        mRecordPrefix = h.finish().hex().substr(0, 12) + "-";
    }

    Key keyOf(std::size_t idx, int frame)
    {
        const GraphNode& node = mGraph.nodes()[idx];
        const NodeDecl& decl = *node.decl;
        if (!mTimeVarying[idx]) frame = kAnyFrame;
        {
            std::lock_guard<std::mutex> lock(mKeyMutex);
            auto it = mKeys[idx].find(frame);
            if (it != mKeys[idx].end()) return it->second;
        }
        // A simulation's key chains through its history; walk it forward without recursion.
        Key previous;
        if (decl.simulation && frame > mGraph.frames.start) {
            int f = frame - 1;
            {
                std::lock_guard<std::mutex> lock(mKeyMutex);
                while (f > mGraph.frames.start && !mKeys[idx].count(f)) --f;
            }
            for (int g = f; g < frame; ++g) previous = keyOf(idx, g);
        }
        Hasher h;
        h.str("cloudgraph-key-1").str(decl.type).i64(decl.version);
        for (std::size_t i = 0; i < decl.params.size(); ++i) {
            // An input file enters the key by its content (hashExtra), never by its path.
            if (decl.params[i].role == ParamRole::InputFile) continue;
            h.str(decl.params[i].name);
            hashParam(h, node.params.valueAt(i));
        }
        if (decl.hashExtra) decl.hashExtra(node.params, h);
        if (decl.readsTimeStep) h.str("timeStep").f64(mGraph.timeStep);
        if (decl.readsSeed) h.str("seed").u64(mGraph.seed);
        if (decl.readsFrameRange)
            h.str("frameRange").i64(mGraph.frames.start).i64(mGraph.frames.end);
        if (node.bypass) h.str("bypass");
        for (const PortDecl& port : decl.inputs) {
            h.str(port.name);
            auto it = node.inputs.find(port.name);
            if (it == node.inputs.end()) {
                h.str("<unconnected>");
            } else {
                h.str(it->second.port).key(keyOf(mGraph.indexOf(it->second.node), frame));
            }
        }
        if (dependsOnFrame(decl, node.params)) h.str("frame").i64(frame);
        if (decl.simulation) {
            h.str("start").i64(mGraph.frames.start);
            if (frame > mGraph.frames.start) h.key(previous);
        }
        const Key key = h.finish();
        std::lock_guard<std::mutex> lock(mKeyMutex);
        mKeys[idx][frame] = key;
        return key;
    }

    /// Node indices `targets` need, in topological order.
    std::vector<std::size_t> closure(const std::vector<std::size_t>& targets) const
    {
        std::vector<bool> need(mGraph.nodes().size(), false);
        std::vector<std::size_t> stack(targets);
        while (!stack.empty()) {
            const std::size_t i = stack.back();
            stack.pop_back();
            if (need[i]) continue;
            need[i] = true;
            for (std::size_t up : mGraph.upstream()[i]) stack.push_back(up);
        }
        std::vector<std::size_t> out;
        for (std::size_t i : mGraph.topologicalOrder())
            if (need[i]) out.push_back(i);
        return out;
    }

    /// Cooks (or fetches) `closure` for frames first..last as a pipeline (FramePipeline):
    /// each frame without what resolves ahead; onFrame hears of each frame in order.
    /// `targets`: nodes asked for by name, evaluated even where only a resolved node reads
    /// them.
    void cookRange(const std::vector<std::size_t>& closure, int first, int last,
                   const FrameCallback& onFrame, const std::vector<std::size_t>& targets = {})
    {
        std::vector<bool> anyOrder;
        for (const GraphNode& node : mGraph.nodes())
            anyOrder.push_back(node.decl->framesInAnyOrder);
        FramePipeline(mGraph.upstream(), kFramesInFlight, std::move(anyOrder))
            .run(
                first, last,
                [&](int frame, FrameOutputs& results) {
                    return withoutResolvedAhead(closure, frame, results, targets);
                },
                [&](std::size_t idx, int frame, const FrameOutputs& results) {
                    return evaluate(idx, frame, results);
                },
                [&](int frame, const FrameOutputs& results) {
                    if (onFrame) onFrame(frame, results);
                });
    }

    void addToTotal(std::size_t n) { mTotal += n; }

private:
    /// Nodes whose outputs are there before the frame cooks take them into `results` and drop
    /// out, with every node that only they need (resolvedAhead). Returns the nodes of `closure`
    /// left to evaluate, in the same order.
    std::vector<std::size_t> withoutResolvedAhead(const std::vector<std::size_t>& closure,
                                                  int frame, FrameOutputs& results,
                                                  const std::vector<std::size_t>& targets)
    {
        const std::size_t n = mGraph.nodes().size();
        std::vector<bool> resolved(n, false);
        std::size_t resolvedCount = 0;
        for (std::size_t idx : closure) {
            if (!resolvedAhead(idx, frame, results)) continue;
            resolved[idx] = true;
            ++resolvedCount;
        }
        if (resolvedCount == 0) return closure;
        // Downstream first: a node is needed when nothing in the closure reads it (a target),
        // a needed node reads it, or it writes files that did not verify: a reader's record
        // (a video verified before its last frame, with no files) says nothing of them.
        std::vector<bool> readInClosure(n, false), readByNeeded(n, false), needed(n, false);
        for (std::size_t idx : closure)
            for (std::size_t up : mGraph.upstream()[idx]) readInClosure[up] = true;
        for (std::size_t idx : targets) readInClosure[idx] = false;  // asked for: a target
        for (auto it = closure.rbegin(); it != closure.rend(); ++it) {
            const std::size_t idx = *it;
            const bool writer = WrittenFiles::keepsRecords(*mGraph.nodes()[idx].decl);
            if (resolved[idx] || (readInClosure[idx] && !readByNeeded[idx] && !writer)) continue;
            needed[idx] = true;
            for (std::size_t up : mGraph.upstream()[idx]) readByNeeded[up] = true;
        }
        std::vector<std::size_t> left;
        for (std::size_t idx : closure)
            if (needed[idx]) left.push_back(idx);
        mTotal -= closure.size() - left.size() - resolvedCount;  // resolved ones were reported
        return left;
    }

    /// A writer off its schedule at `frame` (NodeDecl::idleOnFrame), whose outputs are all
    /// file lists: it writes nothing whatever its inputs.
    bool idleWriter(const GraphNode& node, int frame) const
    {
        const NodeDecl& decl = *node.decl;
        if (!decl.writesFiles || !decl.idleOnFrame || node.bypass) return false;
        if (std::any_of(decl.outputs.begin(), decl.outputs.end(),
                        [](const PortDecl& p) { return p.type != "Text"; }))
            return false;
        return decl.idleOnFrame(node.params, frame, mGraph.frames.start);
    }

    /// Whether node idx's outputs at `frame` were put in `results` (and reported) before the
    /// frame cooks, sparing what only it reads: a writer whose files from an earlier run verify
    /// (WrittenFiles), or a cached node that reads a node never stored on disk, which would
    /// otherwise be remade only to be ignored (the Voxelizer's GenerateCloud stream).
    bool resolvedAhead(std::size_t idx, int frame, FrameOutputs& results)
    {
        const GraphNode& node = mGraph.nodes()[idx];
        const NodeDecl& decl = *node.decl;
        const auto t0 = std::chrono::steady_clock::now();
        if (idleWriter(node, frame)) {
            OutputMap empty;
            for (const PortDecl& p : decl.outputs) empty[p.name] = std::make_shared<TextData>("");
            results[idx] = std::make_shared<const OutputMap>(std::move(empty));
            report(idx, frame, keyOf(idx, frame), CookStatus::Idle, "", t0, *results[idx]);
            return true;
        }
        if (WrittenFiles::keepsRecords(decl)) {
            const Key key = keyOf(idx, frame);
            auto recorded = mWritten.verified(key, decl);
            if (!recorded) return false;
            results[idx] = std::make_shared<const OutputMap>(std::move(*recorded));
            report(idx, frame, key, CookStatus::Verified, "", t0, *results[idx]);
            return true;
        }
        if (decl.writesFiles || decl.simulation) return false;  // evaluate() handles those
        const auto& upstream = mGraph.upstream()[idx];
        if (std::none_of(upstream.begin(), upstream.end(),
                         [&](std::size_t up) { return !mGraph.nodes()[up].decl->cacheOnDisk; }))
            return false;
        const Key key = keyOf(idx, frame);
        CookStatus status = CookStatus::Cooked;
        OutputsPtr hit = lookup(key, decl, status);
        if (!hit) return false;
        results[idx] = hit;
        report(idx, frame, key, status, "", t0, *hit);
        return true;
    }

    /// Node idx at `frame`, from the caches or cooked; its inputs are in `results`.
    OutputsPtr evaluate(std::size_t idx, int frame, const FrameOutputs& results)
    {
        mEv.mOptions.cancel->throwIfCancelled();
        const NodeDecl& decl = *mGraph.nodes()[idx].decl;
        const Key key = keyOf(idx, frame);
        const auto t0 = std::chrono::steady_clock::now();

        CookStatus status = CookStatus::Cooked;
        std::string reason;
        OutputsPtr outputs;
        if (!decl.writesFiles) outputs = lookup(key, decl, status);
        if (!outputs) outputs = cook(idx, frame, key, results, reason);  // status stays Cooked
        if (decl.simulation) hold(idx, frame, outputs);
        report(idx, frame, key, status, std::move(reason), t0, *outputs);
        return outputs;
    }

    void report(std::size_t idx, int frame, const Key& key, CookStatus status, std::string reason,
                std::chrono::steady_clock::time_point t0, const OutputMap& outputs)
    {
        const GraphNode& node = mGraph.nodes()[idx];
        CookRecord record;
        record.node = node.id;
        record.type = node.decl->type;
        record.frame = frame;
        record.order = mOrderIndex[idx];
        record.key = key;
        record.status = status;
        record.reason = std::move(reason);
        record.seconds = secondsSince(t0);
        record.bytes = outputBytes(outputs);
        record.values = smallValues(outputs);
        mEv.mReport.add(std::move(record));
        if (mEv.mOptions.onProgress) {
            Progress p;
            p.done = ++mDone;
            p.total = mTotal;
            p.frame = frame;
            p.node = node.id;
            mEv.mOptions.onProgress(p);
        }
    }

    OutputsPtr lookup(const Key& key, const NodeDecl& decl, CookStatus& status)
    {
        if (OutputsPtr hit = decl.cacheInMemory ? mEv.mMemory.find(key) : nullptr) {
            status = CookStatus::MemoryHit;
            return hit;
        }
        if (mEv.mOptions.diskCache && decl.cacheOnDisk) {
            if (auto stored = mEv.mOptions.diskCache->load(key, mEv.mRegistry, &decl.outputs)) {
                auto hit = std::make_shared<const OutputMap>(std::move(*stored));
                if (decl.cacheInMemory) mEv.mMemory.insert(key, hit);
                status = CookStatus::DiskHit;
                return hit;
            }
        }
        return nullptr;
    }

    /// A bypassed node's outputs (Graph::checkBypass allowed them): a writer's empty file
    /// list; any other node's first input, as each of its outputs.
    OutputMap bypassedOutputs(const NodeDecl& decl, const GraphNode& node,
                              const FrameOutputs& results) const
    {
        OutputMap out;
        if (decl.writesFiles) {
            for (const PortDecl& p : decl.outputs) out[p.name] = std::make_shared<TextData>("");
            return out;
        }
        const Connection& conn = node.inputs.at(decl.inputs.front().name);
        const OutputsPtr& up = results[mGraph.indexOf(conn.node)];
        for (const PortDecl& p : decl.outputs) out[p.name] = up->at(conn.port);
        return out;
    }

    OutputsPtr cook(std::size_t idx, int frame, const Key& key, const FrameOutputs& results,
                    std::string& reason)
    {
        const GraphNode& node = mGraph.nodes()[idx];
        const NodeDecl& decl = *node.decl;

        OutputsPtr previous;
        if (decl.simulation && frame > mGraph.frames.start) previous = previousState(idx, frame);

        EvalContext eval;
        eval.frame = frame;
        eval.startFrame = mGraph.frames.start;
        eval.endFrame = mGraph.frames.end;
        eval.timeStep = mGraph.timeStep;
        eval.seed = mGraph.seed;
        eval.allowOutsideOut = mGraph.limits.allowPathsOutsideOut;
        eval.cancel = mEv.mOptions.cancel;
        CookContext ctx(decl, node.id, node.params, eval, mEv.mOptions.outDir);
        nlohmann::json inputKeys = nlohmann::json::object();
        for (const auto& [portName, conn] : node.inputs) {
            const std::size_t up = mGraph.indexOf(conn.node);
            const OutputsPtr& upOut = results[up];
            if (!upOut) throw std::logic_error("input of '" + node.id + "' was not evaluated");
            auto it = upOut->find(conn.port);
            if (it == upOut->end())
                throw std::logic_error("'" + conn.node + "' lacks output '" + conn.port + "'");
            ctx.setInput(portName, it->second);
            inputKeys[portName] = keyOf(up, frame).hex();
        }
        ctx.setPrevious(previous.get());

        reason = mEv.mHistory.explain(mRecordPrefix + node.id, identity(node),
                                      mTimeVarying[idx] ? std::to_string(frame) : "all", inputKeys,
                                      decl.simulation);
        if (decl.writesFiles)
            reason = (WrittenFiles::keepsRecords(decl)
                          ? "writes files (none verified from an earlier run); "
                          : "writes files (cooks on every run); ") +
                     reason;

        OutputMap out;
        try {
            if (node.bypass) {
                out = bypassedOutputs(decl, node, results);
            } else {
                std::unique_ptr<Node> instance = decl.create();
                instance->cook(ctx);
                out = ctx.takeOutputs();
            }
            for (const PortDecl& p : decl.outputs)
                if (!out.count(p.name))
                    throw std::logic_error("did not set output '" + p.name + "'");
        } catch (const Cancelled&) {
            throw;
        } catch (const CookError&) {
            throw;
        } catch (const InputError& e) {
            // Nodes name their parameters as "<id>/params/<name>": made a full JSON pointer.
            if (e.where() == node.id || e.where().rfind(node.id + "/", 0) == 0)
                throw CookError(node.id, mGraph.locate("/nodes/" + e.where()), frame, e.message(),
                                true);
            throw CookError(node.id, mGraph.locate(node.pointer), frame, e.what(), true);
        } catch (const std::invalid_argument& e) {
            // The libraries below the engine report bad input this way: an algorithm's
            // arguments, a file reader's formats::FormatError. Bad input: exit 2, at the node.
            throw CookError(node.id, mGraph.locate(node.pointer), frame, e.what(), true);
        } catch (const std::exception& e) {
            throw CookError(node.id, mGraph.locate(node.pointer), frame, e.what(), false);
        }
        auto shared = std::make_shared<const OutputMap>(std::move(out));
        if (decl.cacheInMemory) mEv.mMemory.insert(key, shared);
        if (mEv.mOptions.diskCache && !decl.writesFiles && decl.cacheOnDisk)
            mEv.mOptions.diskCache->store(key, *shared);
        if (WrittenFiles::keepsRecords(decl)) mWritten.record(key, *shared);
        return shared;
    }

    /// What a node reads that is the same for every frame, for CookHistory.
    nlohmann::json identity(const GraphNode& node) const
    {
        nlohmann::json params = nlohmann::json::object();
        for (std::size_t i = 0; i < node.decl->params.size(); ++i)
            params[node.decl->params[i].name] = paramToString(node.params.valueAt(i));
        nlohmann::json context = nlohmann::json::object();
        if (node.decl->readsTimeStep) context["timeStep"] = mGraph.timeStep;
        if (node.decl->readsSeed) context["seed"] = mGraph.seed;
        if (node.decl->readsFrameRange)
            context["frameRange"] = {mGraph.frames.start, mGraph.frames.end};
        return {{"type", node.decl->type},
                {"version", node.decl->version},
                {"params", params},
                {"context", context}};
    }

    void hold(std::size_t idx, int frame, const OutputsPtr& outputs)
    {
        std::lock_guard<std::mutex> lock(mHeldMutex[idx]);
        mHeld[idx] = {frame, outputs};
    }

    /// The simulation's own output at frame-1: held from the last step, else from a cache,
    /// else recomputed by stepping forward from the latest cached frame (or the start).
    OutputsPtr previousState(std::size_t idx, int frame)
    {
        {
            std::lock_guard<std::mutex> lock(mHeldMutex[idx]);
            if (mHeld[idx].outputs && mHeld[idx].frame == frame - 1) return mHeld[idx].outputs;
        }
        CookStatus ignored;
        int resume = frame - 1;
        OutputsPtr state;
        for (; resume >= mGraph.frames.start; --resume) {
            if ((state = lookup(keyOf(idx, resume), *mGraph.nodes()[idx].decl, ignored))) break;
        }
        if (state) hold(idx, resume, state);
        // Step forward through the frames no cache holds; each step cooks the node's closure.
        const std::vector<std::size_t> nodes = closure({idx});
        if (resume + 1 < frame) {
            addToTotal(nodes.size() * static_cast<std::size_t>(frame - 1 - resume));
            cookRange(nodes, resume + 1, frame - 1, {}, {idx});
        }
        std::lock_guard<std::mutex> lock(mHeldMutex[idx]);
        return mHeld[idx].outputs;
    }

    struct Held {
        int frame = 0;
        OutputsPtr outputs;
    };

    Evaluator& mEv;
    const Graph& mGraph;
    WrittenFiles mWritten;
    std::mutex mKeyMutex;
    std::vector<std::unordered_map<int, Key>> mKeys;
    std::vector<bool> mTimeVarying;
    std::vector<std::size_t> mOrderIndex;
    std::vector<Held> mHeld;
    std::vector<std::mutex> mHeldMutex;
    std::string mRecordPrefix;
    std::atomic<std::size_t> mDone{0};
    std::atomic<std::size_t> mTotal{0};
};

namespace {

/// Writers killed in an earlier run left temp files beside their outputs; the directories
/// this run writes to are the ones where they can be, and are cheap to scan.
void removeOrphansWhereWritersWrite(const Graph& graph, const std::vector<std::size_t>& nodes,
                                    const std::filesystem::path& outDir)
{
    std::set<std::filesystem::path> dirs;
    for (std::size_t idx : nodes) {
        const GraphNode& node = graph.nodes()[idx];
        for (std::size_t i = 0; i < node.decl->params.size(); ++i) {
            if (node.decl->params[i].role != ParamRole::OutputPath) continue;
            const std::filesystem::path file(std::get<std::string>(node.params.valueAt(i)));
            dirs.insert((file.is_relative() ? outDir / file : file).parent_path());
        }
    }
    for (const auto& dir : dirs) util::removeOrphanedTemporaries(dir);
}

}  // namespace

Evaluator::Evaluator(const Registry& registry, EvaluatorOptions options)
    : mRegistry(registry),
      mOptions(std::move(options)),
      mMemory(mOptions.memoryBudgetBytes),
      mHistory(mOptions.diskCache)
{
    if (!mOptions.cancel) mOptions.cancel = std::make_shared<CancelToken>();
}

void Evaluator::cookFrames(const Graph& graph, int first, int last,
                           const std::vector<std::string>& targets, const FrameCallback& onFrame)
{
    if (first > last) throw std::invalid_argument("frame range is empty");
    if (first < graph.frames.start)
        throw std::invalid_argument("frame " + std::to_string(first) +
                                    " is before the graph's start frame");
    Session session(*this, graph);
    std::vector<std::size_t> targetIdx;
    if (targets.empty()) {
        targetIdx = graph.sinks();
    } else {
        for (const std::string& id : targets) targetIdx.push_back(graph.indexOf(id));
    }
    const std::vector<std::size_t> nodes = session.closure(targetIdx);
    session.addToTotal(nodes.size() * static_cast<std::size_t>(last - first + 1));
    removeOrphansWhereWritersWrite(graph, nodes, mOptions.outDir);
    try {
        session.cookRange(nodes, first, last, onFrame, targetIdx);
    } catch (...) {
        mHistory.commit();
        throw;
    }
    mHistory.commit();
}

OutputsPtr Evaluator::pull(const Graph& graph, const std::string& nodeId, int frame)
{
    const std::size_t idx = graph.indexOf(nodeId);
    OutputsPtr out;
    cookFrames(graph, frame, frame, {nodeId}, [&](int, const FrameOutputs& r) { out = r[idx]; });
    return out;
}

Key Evaluator::key(const Graph& graph, const std::string& nodeId, int frame)
{
    Session session(*this, graph);
    return session.keyOf(graph.indexOf(nodeId), frame);
}

}  // namespace cg
