/// A plugin whose registration fails halfway: one valid node type, then one with an
/// undocumented port, which Registry::addNode rejects. The loader must refuse the plugin
/// and leave the registry without the first node type either.

#include <memory>

#include "core/CoreData.h"
#include "core/Node.h"
#include "core/Plugin.h"

namespace {

class PassThrough final : public cg::Node {
public:
    void cook(cg::CookContext& ctx) override
    {
        ctx.setOutput("value", ctx.input<cg::FloatData>("value"));
    }
};

cg::NodeDecl passThrough(const char* type, const char* portDoc)
{
    cg::NodeDecl decl;
    decl.type = type;
    decl.category = "sample";
    decl.doc = "Passes its input through unchanged.";
    decl.inputs = {{"value", "Float", portDoc, false}};
    decl.outputs = {{"value", "Float", "the same value", false}};
    decl.create = [] { return std::make_unique<PassThrough>(); };
    return decl;
}

void registerThrowing(cg::Registry& registry)
{
    registry.addNode(passThrough("ThrowingFirst", "a value"));
    registry.addNode(passThrough("ThrowingSecond", ""));  // undocumented port: rejected
}

}  // namespace

CLOUDGRAPH_PLUGIN(registerThrowing)
