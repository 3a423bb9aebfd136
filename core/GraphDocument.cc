#include "core/GraphDocument.h"

#include <algorithm>
#include <exception>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "core/DiskCache.h"
#include "core/Error.h"
#include "core/GraphFileText.h"
#include "util/AtomicFile.h"

namespace cg {

namespace {

LoadOptions whileBuilding(LoadOptions o)
{
    o.requireComplete = false;
    return o;
}

}  // namespace

GraphDocument::GraphDocument(Graph graph, const Registry& registry)
    : mGraph(std::move(graph)), mRegistry(registry)
{
}

std::unique_ptr<GraphDocument> GraphDocument::load(const std::filesystem::path& path,
                                                   const Registry& registry,
                                                   const LoadOptions& options)
{
    try {
        std::string text = readGraphText(path, options);
        std::unique_ptr<GraphDocument> doc(new GraphDocument(
            parseGraphFile(text, path, registry, whileBuilding(options)), registry));
        doc->mLayout = std::move(text);
        return doc;
    } catch (const InputError& e) {
        if (e.where() == path.string()) throw UnreadableGraph(e.where(), e.message());
        throw;
    }
}

std::unique_ptr<GraphDocument> GraphDocument::parse(const std::string& text,
                                                    const std::string& name,
                                                    const std::string& baseDir,
                                                    const Registry& registry)
{
    LoadOptions o = whileBuilding({});
    o.inputFileBase = baseDir;
    return std::unique_ptr<GraphDocument>(
        new GraphDocument(parseGraph(text, name, registry, o), registry));
}

nlohmann::json GraphDocument::json() const { return graphToJson(mGraph); }

std::string GraphDocument::toJson() const { return json().dump(1); }

void GraphDocument::setParam(const std::string& node, const std::string& param,
                             const nlohmann::json& value)
{
    mGraph.setParam(node, param, value);
    mComplete.reset();
}

void GraphDocument::applySetOverride(const std::string& assignment)
{
    cg::applySetOverride(mGraph, assignment);
    mComplete.reset();
}

void GraphDocument::replace(const std::string& text)
{
    Graph edited = parseGraph(text, mGraph.sourceName(), mRegistry, whileBuilding(mGraph.limits));
    edited.source = mGraph.source;
    mGraph = std::move(edited);
    mComplete.reset();
}

void GraphDocument::reload(const std::string& fileText)
{
    replace(fileText);
    mLayout = fileText;
}

const Graph& GraphDocument::completeGraph() const
{
    if (!mComplete) {
        LoadOptions o = mGraph.limits;
        o.requireComplete = true;
        Graph g = parseGraph(toJson(), mGraph.sourceName(), mRegistry, o);
        g.source = mGraph.source;
        mComplete = std::move(g);
    }
    return *mComplete;
}

std::string GraphDocument::save(const std::filesystem::path& path)
{
    completeGraph();
    std::string text = graphFileText(mGraph, mLayout);
    try {
        util::saveFileAtomically(path, text);
    } catch (const std::exception& e) {
        throw InputError(path.string(), std::string("cannot write the graph: ") + e.what());
    }
    mLayout = text;
    return text;
}

Evaluator& GraphDocument::evaluatorFor(const std::string& cache, const std::string& out)
{
    auto& slot = mEvaluators[{cache, out}];
    if (!slot) {
        EvaluatorOptions o;
        o.outDir = out;
        o.onProgress = [this](const Progress& p) {
            std::lock_guard<std::mutex> lock(mCookMutex);
            // Worker threads report out of order: the most done seen; the total as last
            // reported (it shrinks when the cook finds what it need not visit).
            mProgress.done = std::max(mProgress.done, p.done);
            mProgress.total = std::max(p.total, mProgress.done);
            auto& finished = mProgress.finished;  // a node once, though it cooks many frames
            if (std::find(finished.begin(), finished.end(), p.node) == finished.end())
                finished.push_back(p.node);
        };
        if (!cache.empty()) o.diskCache = std::make_shared<DiskCache>(cache);
        slot = std::make_unique<Evaluator>(mRegistry, o);
    }
    return *slot;
}

DataPtr GraphDocument::cook(const Graph& graph, const std::string& node, const std::string& port,
                            int frame, const std::string& cache, const std::string& out,
                            const std::vector<std::string>& alsoCook)
{
    const GraphNode* target = graph.find(node);
    if (!target) throw InputError(graph.locate("/nodes"), "unknown node '" + node + "'");
    if (!target->decl->findOutput(port))
        throw InputError(
            graph.locate(target->pointer),
            "node '" + node + "' (" + target->decl->type + ") has no output port '" + port + "'");
    auto token = std::make_shared<CancelToken>();
    {
        std::lock_guard<std::mutex> lock(mCookMutex);
        if (mCancel)
            throw CookInProgress("this graph is already cooking (one cook at a time a graph)");
        mCancel = token;
        mProgress = CookProgress{};
        mProgress.cooking = true;
        mCookStart = std::chrono::steady_clock::now();
    }
    // Ends the cook on every way out, a cache that cannot be made included: a mark left set
    // would refuse every later cook of this graph.
    struct EndCook {
        GraphDocument& doc;
        Evaluator* evaluator = nullptr;
        ~EndCook() { doc.endCook(evaluator); }
    } end{*this};
    Evaluator& evaluator = evaluatorFor(cache, out);
    end.evaluator = &evaluator;
    evaluator.setCancelToken(token);
    evaluator.report().clear();
    OutputsPtr outputs;
    if (alsoCook.empty()) {
        outputs = evaluator.pull(graph, node, frame);
    } else {
        std::vector<std::string> targets = alsoCook;
        targets.push_back(node);
        const std::size_t index = graph.indexOf(node);
        evaluator.cookFrames(
            graph, frame, frame, targets,
            [&](int, const Evaluator::FrameOutputs& cooked) { outputs = cooked[index]; });
        // Writers whose files still verify are skipped with what only they read: the
        // node was not needed, so pull it on its own (a cache hit, most often).
        if (!outputs) outputs = evaluator.pull(graph, node, frame);
    }
    return outputs->at(port);
}

void GraphDocument::endCook(Evaluator* evaluator) noexcept
{
    std::lock_guard<std::mutex> lock(mCookMutex);
    mCancel.reset();
    mProgress.cooking = false;
    mProgress.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - mCookStart).count();
    try {
        mLastReport = evaluator ? evaluator->report().toJson().dump() : "{}";
    } catch (...) {
        mLastReport = "{}";  // out of memory: the cook's own error says more than its report
    }
}

void GraphDocument::cancel()
{
    std::lock_guard<std::mutex> lock(mCookMutex);
    if (mCancel) mCancel->cancel();
}

CookProgress GraphDocument::progress() const
{
    std::lock_guard<std::mutex> lock(mCookMutex);
    CookProgress p = mProgress;
    if (p.cooking)
        p.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - mCookStart).count();
    return p;
}

std::string GraphDocument::lastReport() const
{
    std::lock_guard<std::mutex> lock(mCookMutex);
    return mLastReport;
}

}  // namespace cg
