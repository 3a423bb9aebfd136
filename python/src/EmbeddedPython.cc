#include "EmbeddedPython.h"

#include <filesystem>
#include <system_error>

#include <pybind11/embed.h>

#include "Bindings.h"
#include "Document.h"
#include "Errors.h"
#include "core/Error.h"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace cg::python {

namespace {

/// The package beside this program in a build tree (build/cli/cloudgraph and
/// build/python/cloudgraph), or empty: an installed package is on Python's own path.
fs::path packageRootBesideProgram()
{
    std::error_code ec;
    const fs::path program = fs::read_symlink("/proc/self/exe", ec);
    if (ec) return {};
    const fs::path root = program.parent_path().parent_path() / "python";
    return fs::exists(root / "cloudgraph" / "__init__.py", ec) ? root : fs::path();
}

class Interpreter {
public:
    Interpreter()
    {
        py::module_ sys = py::module_::import("sys");
        const fs::path root = packageRootBesideProgram();
        if (!root.empty()) sys.attr("path").attr("insert")(0, root.string());
        // cloudgraph._cloudgraph is this program's engine, made here: the extension file
        // beside the package would bring a second engine, with its own registry.
        py::module_ engine =
            py::module_::create_extension_module("cloudgraph._cloudgraph", nullptr, &mDefinition);
        defineModule(engine);
        sys.attr("modules")["cloudgraph._cloudgraph"] = engine;
        mSaved = PyEval_SaveThread();  // the engine's threads take the GIL as they need it
    }
    ~Interpreter() { PyEval_RestoreThread(mSaved); }  // then mGuard finalizes Python

private:
    // No Python signal handlers: the CLI's own Ctrl-C handling cancels a run.
    py::scoped_interpreter mGuard{false};
    PyModuleDef mDefinition{};
    PyThreadState* mSaved = nullptr;
};

}  // namespace

void loadPythonNodeFiles(const std::vector<std::string>& files, Registry& registry)
{
    static Interpreter interpreter;
    setSharedRegistry(&registry);
    py::gil_scoped_acquire gil;
    for (const std::string& file : files) {
        try {
            py::module_::import("cloudgraph.nodes").attr("load_file")(file);
        } catch (py::error_already_set& e) {
            throw InputError(file, "cannot load Python nodes:\n" + pythonTraceback(e));
        }
    }
}

}  // namespace cg::python
