// Integrate: the simplest simulation node, state(n) = state(n-1) + timeStep * rate(n).

#include <vector>

#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/util/UtilNodes.h"

namespace cg {

namespace {

class IntegrateNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto rate = ctx.input<FloatArrayData>("rate");
        const auto previous = ctx.previous<FloatArrayData>("state");
        if (!previous) {
            // The start frame holds the initial state; stepping begins with the next frame.
            const auto initial = static_cast<float>(ctx.params().getFloat("initial"));
            ctx.setOutput("state", std::make_shared<FloatArrayData>(
                                       std::vector<float>(rate->values.size(), initial)));
            return;
        }
        if (previous->values.size() != rate->values.size()) {
            throw InputError(ctx.nodeId(), "input 'rate' changed length during the simulation");
        }
        const auto dt = static_cast<float>(ctx.timeStep());
        std::vector<float> state(previous->values);
        for (std::size_t i = 0; i < state.size(); ++i) state[i] += dt * rate->values[i];
        ctx.setOutput("state", std::make_shared<FloatArrayData>(std::move(state)));
    }
};

}  // namespace

void registerIntegrateNode(Registry& registry)
{
    NodeDecl d;
    d.type = "Integrate";
    d.category = "util";
    d.doc =
        "Explicit Euler integration: state = initial on the start frame, then "
        "state(n) = state(n-1) + timeStep * rate(n). A simulation: frame n is stepped "
        "from the cached frame n-1.";
    d.simulation = true;
    d.readsTimeStep = true;
    d.inputs = {port("rate", "FloatArray", "rate of change per second")};
    d.outputs = {port("state", "FloatArray", "the integrated values")};
    d.params = {floatParam("initial", 0.0, "", "every element's value on the start frame")};
    d.create = [] { return std::make_unique<IntegrateNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
