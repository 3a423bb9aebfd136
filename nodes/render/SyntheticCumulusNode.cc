// SyntheticCumulus: a cauliflower cumulus fog volume from a hierarchy of noisy spheres.

#include <memory>

#include "algo/render/scenes/SyntheticCumulus.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/FogVolume.h"
#include "nodes/render/RenderNodes.h"

namespace cg {

namespace {

algo::SyntheticCumulusSettings settingsFrom(const ParamSet& p)
{
    algo::SyntheticCumulusSettings s;
    s.seed = static_cast<std::uint64_t>(p.getInt("seed"));
    s.voxelSize = p.getFloat("voxelSize");
    s.baseHeight = p.getFloat("baseHeight");
    s.baseRadius = p.getFloat("baseRadius");
    s.towerHeight = p.getFloat("towerHeight");
    s.levels = static_cast<int>(p.getInt("levels"));
    s.children = static_cast<int>(p.getInt("children"));
    s.edgeSoftness = p.getFloat("edgeSoftness");
    s.noiseAmplitude = p.getFloat("noiseAmplitude");
    s.noiseScale = p.getFloat("noiseScale");
    s.density = p.getFloat("density");
    return s;
}

class SyntheticCumulusNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const algo::SyntheticCumulusSettings s = settingsFrom(ctx.params());
        const auto blobs = algo::cumulusBlobs(s);
        ctx.checkCancelled();
        openvdb::FloatGrid::Ptr grid = algo::rasterizeCumulus(blobs, s);
        ctx.checkCancelled();
        ctx.setOutput("volume", std::make_shared<FogVolumeData>(grid));
    }
};

}  // namespace

void registerSyntheticCumulusNode(Registry& registry)
{
    const algo::SyntheticCumulusSettings def;
    NodeDecl d;
    d.type = "SyntheticCumulus";
    d.version = 1;
    d.category = "render";
    d.doc =
        "A test cumulus that needs no particles: 7 base blobs whose bottoms are cut flat at "
        "the cloud base, then `children` smaller blobs (0.55-0.7 x the parent radius) on the "
        "upper side of each blob of the level below, pulled toward the axis; soft spheres "
        "summed and clamped to 1, their edges eroded by billow noise; rasterised leaf by leaf "
        "into a sparse fog volume 'density' (values in [0, 1]). Deterministic for a seed. All "
        "shape values are our choice, not the paper's.";
    d.outputs = {port("volume", "FogVolume", "the cloud density, fog volume in metres")};
    d.params = {
        intParam("seed", 1, "", "random seed of the blob layout and noise", 0, 1e15),
        floatParam("voxelSize", def.voxelSize, "m", "voxel edge", 1, 1000),
        floatParam("baseHeight", def.baseHeight, "m", "height of the flat cloud base", 0, 20000),
        floatParam("baseRadius", def.baseRadius, "m", "half-width of the footprint", 10, 20000),
        floatParam("towerHeight", def.towerHeight, "",
                   "vertical stretch of the blob pile (1 = about as tall as wide)", 0.2, 5),
        intParam("levels", def.levels, "", "levels of the blob hierarchy", 1, 6),
        intParam("children", def.children, "", "blobs on each blob of the level below", 1, 8),
        floatParam("edgeSoftness", def.edgeSoftness, "",
                   "fraction of a blob's radius over which it fades out", 0.01, 1),
        floatParam("noiseAmplitude", def.noiseAmplitude, "",
                   "edge erosion by billow noise, 0 = smooth spheres", 0, 0.95),
        floatParam("noiseScale", def.noiseScale, "m", "wavelength of the largest noise octave", 1,
                   1e5),
        floatParam("density", def.density, "", "interior density", 0.01, 1),
    };
    d.validate = [](const ParamSet& p, const ParamChecker& check) {
        const std::uint64_t n = algo::cumulusVoxelBound(settingsFrom(p));
        check.checkAllocation("voxelSize",
                              {static_cast<std::int64_t>(std::min<std::uint64_t>(n, 1ull << 62))},
                              sizeof(float));
    };
    d.create = [] { return std::make_unique<SyntheticCumulusNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
