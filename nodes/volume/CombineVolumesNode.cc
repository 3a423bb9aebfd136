// CombineVolumes: two fog volumes on the same voxel grid into one (the maximum or the clamped
// sum per voxel), e.g. the cloud and its lighter vapour in Figure 5.

#include <memory>
#include <stdexcept>
#include <string>

#include "algo/volume/CombineVolumes.h"
#include "core/Error.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/FogVolume.h"
#include "nodes/volume/VolumeNodes.h"

namespace cg {

namespace {

class CombineVolumesNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto a = ctx.input<FogVolumeData>("a");
        const auto b = ctx.input<FogVolumeData>("b");
        openvdb::FloatGrid::Ptr out;
        try {
            out = algo::combineFogVolumes(
                *a->grid, *b->grid, algo::combineModeFromName(ctx.params().getString("mode")));
        } catch (const std::invalid_argument& e) {
            throw InputError(ctx.nodeId(), std::string("inputs 'a' and 'b': ") + e.what());
        }
        ctx.setOutput("volume", std::make_shared<FogVolumeData>(out));
    }
};

}  // namespace

void registerCombineVolumesNode(Registry& registry)
{
    NodeDecl d;
    d.type = "CombineVolumes";
    d.category = "volume";
    d.doc =
        "Combines two fog volumes on the same voxel grid (equal transforms, else an error "
        "naming the node) voxel by voxel: 'max' keeps the larger density, 'sum' adds them and "
        "clamps to 1 (openvdb::tools::compMax / compSum). The result is a fog volume named "
        "'density' with a's metadata; the inputs are left untouched.";
    d.inputs = {port("a", "FogVolume", "the first volume (its metadata is kept)"),
                port("b", "FogVolume", "the second volume")};
    d.outputs = {
        port("volume", "FogVolume", "the combined density, values in [0, 1] for fog inputs")};
    d.params = {stringParam("mode", "max", "max: larger density; sum: added, clamped to 1",
                            {"max", "sum"})};
    d.create = [] { return std::make_unique<CombineVolumesNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
