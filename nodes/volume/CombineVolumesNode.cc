// CombineVolumes: two fog volumes on the same voxel grid into one (the maximum or the clamped
// sum per voxel), e.g. the cloud and its lighter vapour in Figure 5.

#include <cstdio>
#include <memory>
#include <string>

#include <openvdb/tools/Composite.h>

#include "core/Error.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/FogVolume.h"
#include "nodes/volume/VolumeNodes.h"

namespace cg {

namespace {

std::string metres(double v)
{
    char text[32];
    std::snprintf(text, sizeof text, "%g m", v);
    return text;
}

class CombineVolumesNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto a = ctx.input<FogVolumeData>("a");
        const auto b = ctx.input<FogVolumeData>("b");
        // Voxel (i, j, k) must be the same place in both, or the combination is meaningless.
        if (a->grid->transform() != b->grid->transform())
            throw InputError(ctx.nodeId(), "inputs 'a' and 'b' have different transforms (voxel "
                                           "size " + metres(a->grid->voxelSize()[0]) + " against " +
                                               metres(b->grid->voxelSize()[0]) +
                                               "): give both Voxelizers the same voxelSize");
        // The composite operators take their operands' trees: work on copies of the cached,
        // immutable inputs.
        openvdb::FloatGrid::Ptr out = a->grid->deepCopy();
        openvdb::FloatGrid::Ptr other = b->grid->deepCopy();
        if (ctx.params().getString("mode") == "max") {
            openvdb::tools::compMax(*out, *other);
        } else {
            openvdb::tools::compSum(*out, *other);
            openvdb::tools::foreach(out->beginValueOn(), [](const openvdb::FloatGrid::ValueOnIter& it) {
                if (*it > 1.0f) it.setValue(1.0f);
            });
        }
        out->setName("density");
        out->setGridClass(openvdb::GRID_FOG_VOLUME);
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
    d.outputs = {port("volume", "FogVolume", "the combined density, values in [0, 1] for fog inputs")};
    d.params = {stringParam("mode", "max", "max: larger density; sum: added, clamped to 1", {"max", "sum"})};
    d.create = [] { return std::make_unique<CombineVolumesNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
