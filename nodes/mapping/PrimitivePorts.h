#pragma once
/// The primitive inputs PrimitiveMapper and GenerateCloud share: 'primitive', and up to three
/// more primitive sets ('primitive2' .. 'primitive4') that copies draw from by their source
/// (algo::primitiveOf), so neighbouring towers do not share an outline (ours).

#include <vector>

#include "core/NodeDecl.h"
#include "nodes/mapping/MappingViews.h"

namespace cg {

class CookContext;

/// The ports: 'primitive' required, the others optional.
std::vector<PortDecl> primitivePorts();

/// The connected primitive sets, in port order.
PrimitiveInputs primitiveInputs(CookContext& ctx);

}  // namespace cg
