#include "EmbeddedPython.h"

#include <filesystem>
#include <stdexcept>
#include <string>
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

/// The package directory this program goes with: in the build tree beside it
/// (build/cli/cloudgraph and build/python/cloudgraph), else installed beside it
/// (P/bin/cloudgraph and P/CLOUDGRAPH_PYTHON_INSTALL_DIR/cloudgraph, as `cmake --install` puts
/// them); else empty, and only Python's own site directories can provide it.
fs::path packageBesideProgram()
{
    std::error_code ec;
    const fs::path program = fs::read_symlink("/proc/self/exe", ec);
    if (ec) return {};
    const fs::path prefix = program.parent_path().parent_path();
    for (const fs::path& root : {prefix / "python", prefix / CLOUDGRAPH_PYTHON_INSTALL_DIR})
        if (fs::exists(root / "cloudgraph" / "__init__.py", ec)) return root / "cloudgraph";
    return {};
}

/// Imports the package in `dir` as `cloudgraph` without putting its parent on sys.path: an
/// install directory such as /usr/local/lib/python3.11/dist-packages holds other modules,
/// which must not come before the standard library.
void importPackageFrom(const fs::path& dir)
{
    py::module_ util = py::module_::import("importlib.util");
    py::list locations;
    locations.append(dir.string());
    py::object spec =
        util.attr("spec_from_file_location")("cloudgraph", (dir / "__init__.py").string(),
                                             py::arg("submodule_search_locations") = locations);
    py::object package = util.attr("module_from_spec")(spec);
    py::dict modules = py::module_::import("sys").attr("modules");
    modules["cloudgraph"] = package;
    try {
        spec.attr("loader").attr("exec_module")(package);
    } catch (py::error_already_set&) {
        PyDict_DelItemString(modules.ptr(), "cloudgraph");
        throw;
    }
}

/// The configuration of an isolated interpreter (as `python3 -I`): neither the working
/// directory nor the nodes file's directory goes on sys.path, PYTHON* environment variables
/// and the user's site directory are ignored, and the standard library is found from the
/// interpreter the program was built for, not from the first python3 on PATH (which could
/// bring a virtual environment's site-packages). A module in the directory a command is run
/// from, or an environment inherited from a shell, must not run code before the nodes file
/// the user named.
class IsolatedConfig {
public:
    IsolatedConfig()
    {
        PyConfig_InitIsolatedConfig(&mConfig);  // isolated, safe_path, no env, no user site
        // No Python signal handlers: the CLI's own Ctrl-C handling cancels a run.
        mConfig.install_signal_handlers = 0;
        const PyStatus status =
            PyConfig_SetBytesString(&mConfig, &mConfig.program_name, CLOUDGRAPH_PYTHON_EXECUTABLE);
        if (PyStatus_Exception(status)) {
            PyConfig_Clear(&mConfig);
            throw std::runtime_error("cannot configure Python: " +
                                     std::string(status.err_msg ? status.err_msg : "no memory"));
        }
    }
    IsolatedConfig(const IsolatedConfig&) = delete;
    IsolatedConfig& operator=(const IsolatedConfig&) = delete;

    /// Handed to the interpreter, which clears it once it has started.
    PyConfig* get() { return &mConfig; }

private:
    PyConfig mConfig;
};

class Interpreter {
public:
    Interpreter()
    {
        // cloudgraph._cloudgraph is this program's engine, made here: the extension file
        // beside the package would bring a second engine, with its own registry.
        py::module_ engine =
            py::module_::create_extension_module("cloudgraph._cloudgraph", nullptr, &mDefinition);
        defineModule(engine);
        py::module_::import("sys").attr("modules")["cloudgraph._cloudgraph"] = engine;
        const fs::path package = packageBesideProgram();
        if (!package.empty()) importPackageFrom(package);
        mSaved = PyEval_SaveThread();  // the engine's threads take the GIL as they need it
    }
    ~Interpreter() { PyEval_RestoreThread(mSaved); }  // then mGuard finalizes Python

private:
    IsolatedConfig mConfig;
    // Not pybind11's default of '' (the working directory) at the head of sys.path.
    py::scoped_interpreter mGuard{mConfig.get(), 0, nullptr, /*add_program_dir_to_path=*/false};
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
