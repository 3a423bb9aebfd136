#include "core/NodeDeclJson.h"

namespace cg {

namespace {

nlohmann::json ports(const std::vector<PortDecl>& decls)
{
    nlohmann::json out = nlohmann::json::array();
    for (const PortDecl& p : decls)
        out.push_back(
            {{"name", p.name}, {"type", p.type}, {"doc", p.doc}, {"optional", p.optional}});
    return out;
}

}  // namespace

nlohmann::json nodeDeclToJson(const NodeDecl& d)
{
    nlohmann::json params = nlohmann::json::array();
    for (const ParamDecl& p : d.params) {
        nlohmann::json j = {{"name", p.name},
                            {"type", paramTypeName(p.type)},
                            {"default", paramToJson(p.defaultValue)},
                            {"units", p.units},
                            {"doc", p.doc},
                            {"role", paramRoleName(p.role)},
                            {"choices", p.choices}};
        j["min"] = p.min ? nlohmann::json(*p.min) : nlohmann::json();
        j["max"] = p.max ? nlohmann::json(*p.max) : nlohmann::json();
        params.push_back(std::move(j));
    }
    return {{"type", d.type},
            {"version", d.version},
            {"category", d.category},
            {"doc", d.doc},
            {"inputs", ports(d.inputs)},
            {"outputs", ports(d.outputs)},
            {"params", params},
            {"frame_dependent", d.frameDependent || d.simulation || bool(d.frameDependentIf)},
            {"simulation", d.simulation},
            {"writes_files", d.writesFiles}};
}

nlohmann::json nodeTypesToJson(const Registry& registry)
{
    nlohmann::json out = nlohmann::json::array();
    for (const NodeDecl* d : registry.nodes()) out.push_back(nodeDeclToJson(*d));
    return out;
}

}  // namespace cg
