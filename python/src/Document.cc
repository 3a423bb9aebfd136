#include "Document.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <future>
#include <string>
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

/// `value` as JSON, as json.dumps would write it, except that a float keeps NaN and
/// infinity for the parameter checks to refuse by name.
nlohmann::json jsonFrom(const py::handle& value)
{
    if (value.is_none()) return nullptr;
    if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
    if (py::isinstance<py::int_>(value)) {
        int overflow = 0;
        const long long i = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
        if (overflow == 0) {
            if (i == -1 && PyErr_Occurred()) throw py::error_already_set();
            return i;
        }
        if (overflow > 0) {  // up to 2^64 - 1, as the JSON reader keeps it
            const unsigned long long u = PyLong_AsUnsignedLongLong(value.ptr());
            if (!PyErr_Occurred()) return u;
            PyErr_Clear();
        }
        // Past 64 bits: a float, as the JSON reader reads such a number (infinite past a
        // double's range, which the checks refuse).
        const double d = PyLong_AsDouble(value.ptr());
        if (!PyErr_Occurred()) return d;
        PyErr_Clear();
        return overflow > 0 ? HUGE_VAL : -HUGE_VAL;
    }
    if (py::isinstance<py::float_>(value)) return value.cast<double>();
    if (py::isinstance<py::str>(value)) return value.cast<std::string>();
    if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
        nlohmann::json array = nlohmann::json::array();
        for (const py::handle item : value) array.push_back(jsonFrom(item));
        return array;
    }
    if (py::isinstance<py::dict>(value)) {
        nlohmann::json object = nlohmann::json::object();
        for (const auto item : value.cast<py::dict>()) {
            if (!py::isinstance<py::str>(item.first))
                throw py::type_error("a parameter's dict keys must be str");
            object[item.first.cast<std::string>()] = jsonFrom(item.second);
        }
        return object;
    }
    throw py::type_error("a parameter value cannot be a " +
                         std::string(py::str(value.get_type().attr("__name__"))));
}

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

void Document::setParam(const std::string& node, const std::string& param, const py::handle& value)
{
    mDoc->setParam(node, param, jsonFrom(value));
}

py::object Document::cook(const std::string& node, const std::string& port, int frame,
                          const std::string& cache, const std::string& out)
{
    if (frame < firstFrame() || frame > lastFrame())
        throw py::value_error("frame " + std::to_string(frame) + " is outside the graph's frames " +
                              std::to_string(firstFrame()) + ":" + std::to_string(lastFrame()));
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
