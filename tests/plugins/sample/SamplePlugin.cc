/// A minimal third-party plugin: one node type, built only against the cloudgraph_core API.
/// Compiled a second time with CLOUDGRAPH_SAMPLE_BAD_ABI to stand in for a plugin built
/// against another engine version.

#include <memory>
#include <vector>

#include "core/CoreData.h"
#include "core/Node.h"
#include "core/Plugin.h"

#ifdef CLOUDGRAPH_SAMPLE_BAD_ABI
// The macro reads the version where it expands, so redefining it here is enough.
static constexpr int kEngineAbiVersion = CLOUDGRAPH_PLUGIN_ABI_VERSION;
#undef CLOUDGRAPH_PLUGIN_ABI_VERSION
#define CLOUDGRAPH_PLUGIN_ABI_VERSION (kEngineAbiVersion + 1)
#endif

namespace {

class SampleGain final : public cg::Node {
public:
    void cook(cg::CookContext& ctx) override
    {
        const auto in = ctx.input<cg::FloatArrayData>("values");
        const double gain = ctx.params().getFloat("gain");
        std::vector<float> out(in->values.size());
        for (std::size_t i = 0; i < out.size(); ++i)
            out[i] = static_cast<float>(in->values[i] * gain);
        ctx.setOutput("values", std::make_shared<cg::FloatArrayData>(std::move(out)));
    }
};

void registerSample(cg::Registry& registry)
{
    cg::ParamDecl gain;
    gain.name = "gain";
    gain.type = cg::ParamType::Float;
    gain.defaultValue = 2.0;
    gain.min = -1000.0;
    gain.max = 1000.0;
    gain.doc = "factor applied to every value";

    cg::NodeDecl decl;
    decl.type = "SampleGain";
    decl.category = "sample";
    decl.doc = "Multiplies every value of a float array by a constant gain (a sample plugin).";
    decl.inputs = {{"values", "FloatArray", "values to scale", false}};
    decl.outputs = {{"values", "FloatArray", "the values times gain", false}};
    decl.params = {gain};
    decl.create = [] { return std::make_unique<SampleGain>(); };
    registry.addNode(std::move(decl));
}

}  // namespace

CLOUDGRAPH_PLUGIN(registerSample)
