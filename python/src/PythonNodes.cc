#include "PythonNodes.h"

#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <utility>
#include <variant>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <nlohmann/json.hpp>

#include "Document.h"
#include "Errors.h"
#include "Values.h"
#include "core/Error.h"
#include "core/Hash.h"
#include "core/Node.h"
#include "formats/FileHash.h"
#include "formats/FormatError.h"
#include "util/SystemMemory.h"

namespace py = pybind11;
using nlohmann::json;

namespace cg::python {

namespace {

/// A parameter value as Python's own: float, int, bool, str, or a list.
py::object paramToPython(const ParamValue& value)
{
    return std::visit([](const auto& v) -> py::object { return py::cast(v); }, value);
}

class PythonNode final : public Node {
public:
    explicit PythonNode(std::string type) : mType(std::move(type)) {}

    void cook(CookContext& ctx) override
    {
        const NodeDecl& decl = ctx.decl();
        py::gil_scoped_acquire gil;
        py::dict inputs;
        for (const PortDecl& port : decl.inputs) {
            const auto value = ctx.input<Data>(port.name);
            inputs[py::str(port.name)] = value ? toPython(value) : py::none();
        }
        py::dict params;
        for (std::size_t i = 0; i < decl.params.size(); ++i)
            params[py::str(decl.params[i].name)] = paramToPython(ctx.params().valueAt(i));

        py::object outputs;
        try {
            outputs = py::module_::import("cloudgraph.nodes")
                          .attr("_cook")(mType, ctx.nodeId(), inputs, params, ctx.frame(),
                                         ctx.startFrame(), ctx.timeStep(), ctx.seed());
        } catch (py::error_already_set& e) {
            throw std::runtime_error("the Python cook raised:\n" + pythonTraceback(e));
        }
        const py::dict returned = outputs.cast<py::dict>();
        for (auto item : returned) {
            const std::string name = py::str(item.first);
            if (!decl.findOutput(name))
                throw std::runtime_error("cook() returned '" + name +
                                         "', which is not a declared output");
        }
        for (const PortDecl& port : decl.outputs) {
            if (!returned.contains(port.name))
                throw std::runtime_error("cook() returned no output '" + port.name + "'");
            ctx.setOutput(port.name, fromPython(returned[py::str(port.name)], port.type,
                                                "output '" + port.name + "'"));
        }
        ctx.checkCancelled();
    }

private:
    std::string mType;
};

template <class Enum, class NameOf>
Enum enumFromName(const std::string& name, std::initializer_list<Enum> values, NameOf nameOf,
                  const std::string& where, const char* what)
{
    for (Enum v : values)
        if (name == nameOf(v)) return v;
    throw InputError(where, "unknown " + std::string(what) + " '" + name + "'");
}

std::vector<PortDecl> portsFrom(const json& ports)
{
    std::vector<PortDecl> out;
    for (const json& p : ports)
        out.push_back({p.at("name"), p.at("type"), p.at("doc"), p.value("optional", false)});
    return out;
}

ParamDecl paramFrom(const json& p, const std::string& where)
{
    ParamDecl d;
    d.name = p.at("name");
    const std::string at = where + "/params/" + d.name;
    d.type = enumFromName(p.at("type").get<std::string>(),
                          {ParamType::Float, ParamType::Int, ParamType::Bool, ParamType::String,
                           ParamType::Vector3, ParamType::FloatList, ParamType::IntList},
                          paramTypeName, at, "parameter type");
    // A graph may not name a program, and a Python node that writes files would need the
    // writers' bookkeeping (WrittenFiles): only plain values and input files.
    d.role =
        enumFromName(p.at("role").get<std::string>(), {ParamRole::Plain, ParamRole::InputFile},
                     paramRoleName, at, "parameter role (a Python node's are plain or input_file)");
    if (d.role == ParamRole::InputFile && d.type != ParamType::String)
        throw InputError(at, "an input_file parameter must be a string (a file name)");
    if (!p.at("min").is_null()) d.min = p.at("min").get<double>();
    if (!p.at("max").is_null()) d.max = p.at("max").get<double>();
    d.units = p.at("units");
    d.doc = p.at("doc");
    d.choices = p.at("choices").get<std::vector<std::string>>();
    d.defaultValue = paramFromJson(p.at("default"), d, at + "/default");
    return d;
}

NodeDecl declFrom(const json& j)
{
    NodeDecl d;
    d.type = j.at("type");
    const std::string where = "python node " + d.type;
    d.version = j.at("version");
    d.category = j.at("category");
    d.doc = j.at("doc");
    d.inputs = portsFrom(j.at("inputs"));
    d.outputs = portsFrom(j.at("outputs"));
    for (const json& p : j.at("params")) d.params.push_back(paramFrom(p, where));
    d.frameDependent = j.at("frame_dependent");
    d.readsTimeStep = j.at("reads_time_step");
    d.readsSeed = j.at("reads_seed");
    d.create = [type = d.type] { return std::make_unique<PythonNode>(type); };
    d.hashExtra = [source = j.at("source_hash").get<std::string>()](const ParamSet& params,
                                                                    Hasher& h) {
        // The engine keys declarations and parameter values; the code is the module's.
        h.str("python source").str(source);
        for (std::size_t i = 0; i < params.decls().size(); ++i) {
            const ParamDecl& p = params.decls()[i];
            if (p.role != ParamRole::InputFile) continue;
            const std::string& file = std::get<std::string>(params.valueAt(i));
            try {
                h.str(p.name).u64(
                    formats::fileContentHash(file, util::nodeAllocationLimitBytes(), "input file"));
            } catch (const formats::FormatError&) {
                // The cook reads it and fails with its own reason; the path stands in.
                h.str(p.name).str(file);
            }
        }
    };
    return d;
}

}  // namespace

void registerPythonNode(const std::string& declarationJson)
{
    static std::mutex mutex;
    static std::map<std::string, std::string> declared;  // type -> its declaration
    const json j = json::parse(declarationJson);
    const std::string type = j.at("type");
    std::lock_guard<std::mutex> lock(mutex);
    Registry& registry = sharedRegistry();
    if (registry.findNode(type)) {
        const auto same = declared.find(type);
        if (same != declared.end() && same->second == declarationJson) return;
        throw InputError("python node " + type,
                         "a node type '" + type + "' is already registered" +
                             (same != declared.end() ? " with another declaration or code "
                                                       "(restart Python to change it)"
                                                     : ""));
    }
    try {
        registry.addNode(declFrom(j));
    } catch (const std::invalid_argument& e) {
        throw InputError("python node " + type, e.what());
    }
    declared[type] = declarationJson;
}

}  // namespace cg::python
