#pragma once
/// Python nodes for the CLI (`--python-nodes module.py`): a Python interpreter inside the
/// `cloudgraph` program, whose package cloudgraph uses this program's own engine.

#include <string>
#include <vector>

namespace cg {
class Registry;
}

namespace cg::python {

/// Runs each Python file (a module of @cloudgraph.node classes), registering its node types
/// into `registry`, which must outlive every cook. The interpreter starts on the first call
/// and stops when the program exits; between calls no thread holds the GIL, so the engine's
/// threads can cook Python nodes. A file that cannot be run is an InputError naming it, with
/// the Python traceback.
void loadPythonNodeFiles(const std::vector<std::string>& files, Registry& registry);

}  // namespace cg::python
