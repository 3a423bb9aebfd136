#include "Document.h"

#include <chrono>
#include <cstdlib>
#include <exception>
#include <future>
#include <thread>

#include <nlohmann/json.hpp>

#include "Errors.h"
#include "Values.h"
#include "core/DiskCache.h"
#include "core/Error.h"
#include "core/Plugin.h"
#include "nodes/Builtin.h"
#include "util/AtomicFile.h"

namespace py = pybind11;

namespace cg::python {

namespace {

/// How often a waiting cook looks for Ctrl-C.
constexpr std::chrono::milliseconds kSignalPoll{50};

/// A graph being built may lack nodes or wires; cook and save check it whole.
LoadOptions buildingOptions(LoadOptions o = {})
{
    o.requireComplete = false;
    return o;
}

}  // namespace

namespace {
Registry* gRegistryOverride = nullptr;
}  // namespace

void setSharedRegistry(Registry* registry) { gRegistryOverride = registry; }

Registry& sharedRegistry()
{
    if (gRegistryOverride) return *gRegistryOverride;
    static Registry registry = [] {
        Registry r;
        registerBuiltinNodes(r);
        loadPluginsFromSearchPath(std::getenv("CLOUDGRAPH_PLUGIN_PATH"), r);
        return r;
    }();
    return registry;
}

Document::Document(Graph graph) : mGraph(std::move(graph)) {}

std::unique_ptr<Document> Document::load(const std::string& path)
{
    try {
        return std::unique_ptr<Document>(
            new Document(loadGraph(path, sharedRegistry(), buildingOptions())));
    } catch (const InputError& e) {
        // loadGraph names the file alone, with no place in it, when it cannot read it.
        if (e.where() == path) throw UnreadableGraphFile(e.where(), e.message());
        throw;
    }
}

std::unique_ptr<Document> Document::parse(const std::string& text, const std::string& name,
                                          const std::string& baseDir)
{
    LoadOptions o = buildingOptions();
    o.inputFileBase = baseDir;
    return std::unique_ptr<Document>(new Document(parseGraph(text, name, sharedRegistry(), o)));
}

std::string Document::toJson() const { return graphToJson(mGraph).dump(1); }

void Document::setParam(const std::string& node, const std::string& param,
                        const std::string& valueJson)
{
    mGraph.setParam(node, param, nlohmann::json::parse(valueJson));
}

void Document::replace(const std::string& text)
{
    Graph edited =
        parseGraph(text, mGraph.sourceName(), sharedRegistry(), buildingOptions(mGraph.limits));
    edited.source = mGraph.source;
    mGraph = std::move(edited);
}

Graph Document::completeGraph() const
{
    LoadOptions o = mGraph.limits;
    o.requireComplete = true;
    Graph g = parseGraph(toJson(), mGraph.sourceName(), sharedRegistry(), o);
    g.source = mGraph.source;
    return g;
}

void Document::save(const std::string& path) const
{
    completeGraph();
    try {
        util::writeFileAtomically(path, toJson() + "\n");
    } catch (const std::exception& e) {
        throw InputError(path, std::string("cannot write the graph: ") + e.what());
    }
}

Evaluator& Document::evaluatorFor(const std::string& cache, const std::string& out)
{
    auto& slot = mEvaluators[{cache, out}];
    if (!slot) {
        EvaluatorOptions o;
        o.outDir = out;
        if (!cache.empty()) o.diskCache = std::make_shared<DiskCache>(cache);
        slot = std::make_unique<Evaluator>(sharedRegistry(), o);
    }
    return *slot;
}

py::object Document::cook(const std::string& node, const std::string& port, int frame,
                          const std::string& cache, const std::string& out)
{
    const Graph graph = completeGraph();
    const GraphNode* target = graph.find(node);
    if (!target) throw InputError(graph.locate("/nodes"), "unknown node '" + node + "'");
    if (!target->decl->findOutput(port))
        throw InputError(
            graph.locate(target->pointer),
            "node '" + node + "' (" + target->decl->type + ") has no output port '" + port + "'");
    Evaluator& evaluator = evaluatorFor(cache, out);
    auto token = std::make_shared<CancelToken>();
    {
        std::lock_guard<std::mutex> lock(mCancelMutex);
        if (mCancel)
            throw std::runtime_error("this graph is already cooking (one cook at a time a graph)");
        mCancel = token;
    }
    evaluator.setCancelToken(token);
    evaluator.report().clear();

    OutputsPtr outputs;
    std::exception_ptr failure;
    std::unique_ptr<py::error_already_set> interrupt;
    {
        // The cook runs on a thread of its own while this one, holding the GIL only briefly,
        // looks for Ctrl-C: Python runs signal handlers on its main thread alone.
        py::gil_scoped_release release;
        std::packaged_task<void()> task([&] {
            try {
                outputs = evaluator.pull(graph, node, frame);
            } catch (...) {
                failure = std::current_exception();
            }
        });
        std::future<void> done = task.get_future();
        std::thread worker(std::move(task));
        while (done.wait_for(kSignalPoll) != std::future_status::ready) {
            py::gil_scoped_acquire acquire;
            if (!interrupt && PyErr_CheckSignals() != 0) {
                interrupt = std::make_unique<py::error_already_set>();  // takes the error
                token->cancel();
            }
        }
        worker.join();
    }
    {
        std::lock_guard<std::mutex> lock(mCancelMutex);
        mCancel.reset();
    }
    mLastReport = evaluator.report().toJson().dump();
    if (interrupt) throw std::move(*interrupt);
    if (failure) std::rethrow_exception(failure);
    return toPython(outputs->at(port));
}

void Document::cancel()
{
    std::lock_guard<std::mutex> lock(mCancelMutex);
    if (mCancel) mCancel->cancel();
}

}  // namespace cg::python
