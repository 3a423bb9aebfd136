// Constant, Oscillator and RandomField: nodes with no inputs.

#include <cmath>
#include <vector>

#include "algo/CounterRandom.h"
#include "core/CoreData.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/util/UtilNodes.h"

namespace cg {

namespace {

class ConstantNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        ctx.setOutput("value", std::make_shared<FloatData>(ctx.params().getFloat("value")));
    }
};

class OscillatorNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const ParamSet& p = ctx.params();
        const double t = ctx.frame() * ctx.timeStep();
        const double v = p.getFloat("offset") +
                         p.getFloat("amplitude") * std::sin(2.0 * M_PI * t / p.getFloat("period"));
        ctx.setOutput("value", std::make_shared<FloatData>(v));
    }
};

class RandomFieldNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const ParamSet& p = ctx.params();
        const auto count = static_cast<std::size_t>(p.getInt("width") * p.getInt("height"));
        const auto seed = static_cast<std::uint64_t>(p.getInt("seed"));
        const double low = p.getFloat("low");
        const double span = p.getFloat("high") - low;
        std::vector<float> values(count);
        for (std::size_t i = 0; i < count; ++i) {
            if ((i & 0xffff) == 0) ctx.checkCancelled();
            values[i] = static_cast<float>(low + span * algo::counterUniform(seed, 0, i));
        }
        ctx.setOutput("values", std::make_shared<FloatArrayData>(std::move(values)));
    }
};

}  // namespace

void registerSourceNodes(Registry& registry)
{
    NodeDecl constant;
    constant.type = "Constant";
    constant.category = "util";
    constant.doc = "A number, set by its parameter.";
    constant.outputs = {port("value", "Float", "the parameter's value")};
    constant.params = {floatParam("value", 1.0, "", "the number to output")};
    constant.create = [] { return std::make_unique<ConstantNode>(); };
    registry.addNode(std::move(constant));

    NodeDecl osc;
    osc.type = "Oscillator";
    osc.category = "util";
    osc.doc =
        "offset + amplitude * sin(2 pi t / period), with t = frame * timeStep: a value "
        "that changes every frame.";
    osc.frameDependent = true;
    osc.readsTimeStep = true;
    osc.outputs = {port("value", "Float", "the oscillator's value at this frame")};
    osc.params = {floatParam("amplitude", 1.0, "", "half the peak-to-peak swing"),
                  floatParam("period", 24.0, "s", "time of one full cycle", 1e-6),
                  floatParam("offset", 1.0, "", "the value around which it swings")};
    osc.create = [] { return std::make_unique<OscillatorNode>(); };
    registry.addNode(std::move(osc));

    NodeDecl field;
    field.type = "RandomField";
    field.category = "util";
    field.doc =
        "width x height uniform random values in [low, high), row-major. Value i is a "
        "pure function of (seed, i), so the field is identical for any thread count.";
    field.outputs = {port("values", "FloatArray", "the field, row-major")};
    field.params = {intParam("width", 64, "cells", "number of columns", 1, 1099511627776.0),
                    intParam("height", 64, "cells", "number of rows", 1, 1099511627776.0),
                    intParam("seed", 0, "", "random seed", 0),
                    floatParam("low", 0.0, "", "smallest value (inclusive)"),
                    floatParam("high", 1.0, "", "largest value (exclusive)")};
    field.validate = [](const ParamSet& p, const ParamChecker& check) {
        check.checkAllocation("width", {p.getInt("width"), p.getInt("height")}, sizeof(float));
    };
    field.create = [] { return std::make_unique<RandomFieldNode>(); };
    registry.addNode(std::move(field));
}

}  // namespace cg
