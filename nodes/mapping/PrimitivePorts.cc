#include "nodes/mapping/PrimitivePorts.h"

#include <string>

#include "core/Node.h"
#include "nodes/DeclHelpers.h"

namespace cg {

namespace {

const char* const kExtraPorts[] = {"primitive2", "primitive3", "primitive4"};

}  // namespace

std::vector<PortDecl> primitivePorts()
{
    std::vector<PortDecl> ports{
        port("primitive", "PrimitiveSet", "the 3D cloud primitive set (N_f(s), P_f(s))")};
    for (const char* name : kExtraPorts)
        ports.push_back(port(name, "PrimitiveSet",
                             "another primitive set (ours): each copy plays one of the connected "
                             "sets, drawn by its source",
                             true));
    return ports;
}

PrimitiveInputs primitiveInputs(CookContext& ctx)
{
    PrimitiveInputs out{ctx.input<PrimitiveSetData>("primitive")};
    for (const char* name : kExtraPorts)
        if (auto p = ctx.input<PrimitiveSetData>(name)) out.push_back(std::move(p));
    return out;
}

}  // namespace cg
