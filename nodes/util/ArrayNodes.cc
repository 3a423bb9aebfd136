// Scale and Sum: element-wise arithmetic on FloatArray values.

#include <vector>

#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/util/UtilNodes.h"

namespace cg {

namespace {

class ScaleNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto in = ctx.input<FloatArrayData>("values");
        const auto factorInput = ctx.input<FloatData>("factor");
        const double factor = factorInput ? factorInput->value : ctx.params().getFloat("factor");
        std::vector<float> out(in->values.size());
        for (std::size_t i = 0; i < out.size(); ++i)
            out[i] = static_cast<float>(in->values[i] * factor);
        ctx.setOutput("values", std::make_shared<FloatArrayData>(std::move(out)));
    }
};

class SumNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto a = ctx.input<FloatArrayData>("a");
        const auto b = ctx.input<FloatArrayData>("b");
        if (a->values.size() != b->values.size()) {
            throw InputError(ctx.nodeId(), "inputs 'a' and 'b' differ in length (" +
                                               std::to_string(a->values.size()) + " and " +
                                               std::to_string(b->values.size()) + ")");
        }
        std::vector<float> out(a->values.size());
        for (std::size_t i = 0; i < out.size(); ++i) out[i] = a->values[i] + b->values[i];
        ctx.setOutput("values", std::make_shared<FloatArrayData>(std::move(out)));
    }
};

}  // namespace

void registerArrayNodes(Registry& registry)
{
    NodeDecl scale;
    scale.type = "Scale";
    scale.category = "util";
    scale.doc =
        "Multiplies every value by a factor: the 'factor' input when connected, "
        "otherwise the 'factor' parameter.";
    scale.inputs = {port("values", "FloatArray", "values to scale"),
                    port("factor", "Float", "overrides the factor parameter", true)};
    scale.outputs = {port("values", "FloatArray", "the scaled values")};
    scale.params = {floatParam("factor", 1.0, "", "multiplier used when 'factor' is unconnected")};
    scale.create = [] { return std::make_unique<ScaleNode>(); };
    registry.addNode(std::move(scale));

    NodeDecl sum;
    sum.type = "Sum";
    sum.category = "util";
    sum.doc = "Element-wise a + b; both inputs must have the same length.";
    sum.inputs = {port("a", "FloatArray", "first operand"),
                  port("b", "FloatArray", "second operand")};
    sum.outputs = {port("values", "FloatArray", "a + b")};
    sum.create = [] { return std::make_unique<SumNode>(); };
    registry.addNode(std::move(sum));
}

}  // namespace cg
