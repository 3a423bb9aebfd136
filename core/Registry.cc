#include "core/Registry.h"

#include <stdexcept>
#include <variant>

#include <nlohmann/json.hpp>

#include "core/Error.h"

namespace cg {

namespace {

void checkDeclaration(const NodeDecl& d, const Registry& registry)
{
    auto bad = [&](const std::string& what) {
        throw std::invalid_argument("node type '" + d.type + "': " + what);
    };
    if (d.type.empty()) throw std::invalid_argument("node type without a name");
    if (!d.create) bad("no factory");
    if (d.doc.empty()) bad("no documentation");
    auto checkPorts = [&](const std::vector<PortDecl>& ports, const char* kind) {
        for (const PortDecl& p : ports) {
            if (p.name.empty() || p.name.find('.') != std::string::npos)
                bad(std::string(kind) + " port name '" + p.name + "' is empty or has a '.'");
            if (!registry.findDataType(p.type))
                bad(std::string(kind) + " port '" + p.name + "' has unknown type '" + p.type + "'");
            if (p.doc.empty()) bad(std::string(kind) + " port '" + p.name + "' is undocumented");
        }
    };
    checkPorts(d.inputs, "input");
    checkPorts(d.outputs, "output");
    if (d.outputs.empty()) bad("no output port");
    if (d.framesInAnyOrder && (d.simulation || d.writesFiles || d.gathersFrames))
        bad("a simulation, a writer or a gatherer of frames cooks its frames in order");
    for (const ParamDecl& p : d.params) {
        if (p.doc.empty()) bad("parameter '" + p.name + "' is undocumented");
        if (p.role == ParamRole::InputFile && !d.hashExtra)
            bad("input-file parameter '" + p.name + "' needs hashExtra to hash the file's content");
        if (paramTypeOf(p.defaultValue) != p.type)
            bad("parameter '" + p.name + "' default has the wrong type");
        try {
            // The default must pass the same checks as a user's value.
            paramFromJson(paramToJson(p.defaultValue), p, "/default");
        } catch (const InputError& e) {
            bad("parameter '" + p.name + "' default is invalid: " + e.message());
        }
    }
}

}  // namespace

void Registry::addNode(NodeDecl decl)
{
    checkDeclaration(decl, *this);
    if (decl.simulation) decl.frameDependent = true;
    const std::string name = decl.type;
    if (!mNodes.emplace(name, std::make_unique<NodeDecl>(std::move(decl))).second)
        throw std::invalid_argument("node type '" + name + "' is registered twice");
}

void Registry::addDataType(DataTypeInfo info)
{
    if (info.name.empty() || !info.deserialize)
        throw std::invalid_argument("data type needs a name and a deserializer");
    const std::string name = info.name;
    if (!mDataTypes.emplace(name, std::move(info)).second)
        throw std::invalid_argument("data type '" + name + "' is registered twice");
}

const NodeDecl* Registry::findNode(const std::string& type) const
{
    auto it = mNodes.find(type);
    return it == mNodes.end() ? nullptr : it->second.get();
}

const DataTypeInfo* Registry::findDataType(const std::string& name) const
{
    auto it = mDataTypes.find(name);
    return it == mDataTypes.end() ? nullptr : &it->second;
}

std::vector<const NodeDecl*> Registry::nodes() const
{
    std::vector<const NodeDecl*> out;
    for (const auto& [name, decl] : mNodes) out.push_back(decl.get());
    return out;
}

std::vector<const DataTypeInfo*> Registry::dataTypes() const
{
    std::vector<const DataTypeInfo*> out;
    for (const auto& [name, info] : mDataTypes) out.push_back(&info);
    return out;
}

}  // namespace cg
