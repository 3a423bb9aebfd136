#pragma once
/// The graph behind a Python `cloudgraph.Graph`: a GraphDocument of the module's registry,
/// cooked with the GIL released.

#include <memory>
#include <string>

#include <pybind11/pybind11.h>

#include "core/GraphDocument.h"
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

    std::string toJson() const { return mDoc->toJson(); }
    /// Sets one parameter to a plain Python value (None, bool, int, float, str, list, tuple,
    /// dict), checked as loading checks it. A NaN or infinity reaches those checks, which
    /// refuse it as not finite (JSON text could not carry it); another type is a TypeError.
    void setParam(const std::string& node, const std::string& param, const pybind11::handle& value);
    void replace(const std::string& text) { mDoc->replace(text); }
    void save(const std::string& path) { mDoc->save(path); }

    /// Cooks output `port` of `node` at `frame` with the GIL released (GraphDocument::cook),
    /// and converts it to a Python value. A frame outside the graph's frames is a ValueError.
    /// Ctrl-C, or cancel() from another thread, cancels it: nothing partial is cached.
    pybind11::object cook(const std::string& node, const std::string& port, int frame,
                          const std::string& cache, const std::string& out);
    void cancel() { mDoc->cancel(); }
    std::string lastReport() const { return mDoc->lastReport(); }

    /// The name that prefixes the graph's error locations (its file, or from_dict's name).
    const std::string& name() const { return mDoc->graph().sourceName(); }
    int firstFrame() const { return mDoc->graph().frames.start; }
    int lastFrame() const { return mDoc->graph().frames.end; }

private:
    explicit Document(std::unique_ptr<GraphDocument> doc) : mDoc(std::move(doc)) {}

    std::unique_ptr<GraphDocument> mDoc;
};

}  // namespace cg::python
