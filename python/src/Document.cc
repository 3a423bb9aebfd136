#include "Document.h"

#include <chrono>
#include <cstdlib>
#include <exception>
#include <future>
#include <thread>

#include <nlohmann/json.hpp>

#include "Values.h"
#include "core/Plugin.h"
#include "nodes/Builtin.h"

namespace py = pybind11;

namespace cg::python {

namespace {

/// How often a waiting cook looks for Ctrl-C.
constexpr std::chrono::milliseconds kSignalPoll{50};

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

std::unique_ptr<Document> Document::load(const std::string& path)
{
    return std::unique_ptr<Document>(new Document(GraphDocument::load(path, sharedRegistry())));
}

std::unique_ptr<Document> Document::parse(const std::string& text, const std::string& name,
                                          const std::string& baseDir)
{
    return std::unique_ptr<Document>(
        new Document(GraphDocument::parse(text, name, baseDir, sharedRegistry())));
}

void Document::setParam(const std::string& node, const std::string& param,
                        const std::string& valueJson)
{
    mDoc->setParam(node, param, nlohmann::json::parse(valueJson));
}

py::object Document::cook(const std::string& node, const std::string& port, int frame,
                          const std::string& cache, const std::string& out)
{
    DataPtr value;
    std::exception_ptr failure;
    std::unique_ptr<py::error_already_set> interrupt;
    const Graph graph = mDoc->completeGraph();  // while the GIL keeps edits out
    {
        // The cook runs on a thread of its own while this one, holding the GIL only briefly,
        // looks for Ctrl-C: Python runs signal handlers on its main thread alone.
        py::gil_scoped_release release;
        std::packaged_task<void()> task([&] {
            try {
                value = mDoc->cook(graph, node, port, frame, cache, out);
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
                mDoc->cancel();
            }
        }
        worker.join();
    }
    if (interrupt) throw std::move(*interrupt);
    if (failure) std::rethrow_exception(failure);
    return toPython(value);
}

}  // namespace cg::python
