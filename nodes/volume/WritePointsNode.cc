// WritePoints: cloud particles as an OpenVDB point data grid (VDB Points) per frame, for
// Houdini and OpenVDB's point tools; written atomically.

#include <cstddef>
#include <memory>
#include <string>

#include "core/CoreData.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "formats/PointsGrid.h"
#include "formats/VdbFileWriter.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/CloudParticles.h"
#include "nodes/io/WriterSupport.h"
#include "nodes/volume/VolumeNodes.h"

namespace cg {

namespace {

class WritePointsNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto particles = ctx.input<CloudParticlesData>("particles");
        const ParamSet& p = ctx.params();
        formats::PointsGridSettings s;
        s.voxelSize = p.getFloat("voxelSize");
        s.pointsPerVoxel = static_cast<int>(p.getInt("pointsPerVoxel"));
        s.precision = p.getString("precision") == "float" ? formats::PointPrecision::Float
                                                          : formats::PointPrecision::Fixed16;
        // A frame streamed from GenerateCloud passes by chunk by chunk, a few times: nothing
        // frame-sized is made but the grid itself.
        const formats::ParticleChunks chunks = [&](const auto& consume, bool attributes) {
            particles->forEachChunk(
                [&](const algo::CloudChunk& c) {
                    consume({c.first, static_cast<std::size_t>(c.count), c.positions, c.levels,
                             c.sources});
                },
                CloudChunkFields{attributes, attributes}, [&] { ctx.checkCancelled(); });
        };
        const formats::ParticlePointsGridBuilder builder(chunks, s);
        if (!writesSequenceFrame(ctx, /*empty=*/builder.count() == 0)) return;
        const openvdb::points::PointDataGrid::Ptr grid = builder.build();
        grid->insertMeta("frame", openvdb::Int32Metadata(ctx.frame()));
        grid->insertMeta("units", openvdb::StringMetadata("metres"));
        ctx.checkCancelled();

        const std::filesystem::path path = ctx.outputPath("file");
        formats::writeVdbFile(path, grid, "CloudGraph WritePoints", std::nullopt,
                              [&] { ctx.checkCancelled(); });
        ctx.setOutput("files", std::make_shared<TextData>(path.string()));
    }
};

}  // namespace

void registerWritePointsNode(Registry& registry)
{
    NodeDecl d = writerDecl(
        "WritePoints",
        "Writes cloud particles as an OpenVDB point data grid (VDB Points) named 'points', "
        "which Houdini, vdb_print and OpenVDB's point tools read. Each point carries int32 "
        "'level' (recursive level) and int64 'source' (id of the source record); metadata: "
        "frame, units ('metres'). #### in the name becomes the frame number; the file is "
        "written beside the target and renamed, so it appears whole or not at all. A frame "
        "streamed from GenerateCloud is read chunk by chunk, without a frame-sized array. Writes "
        "frames firstFrame, firstFrame + every, ... and, with skipEmpty, only those with a "
        "particle, as WriteVDB does.",
        port("particles", "CloudParticles", "the particles to write"), "points.####.vdb");
    d.version = 2;         // each version's change: CHANGES.md, "Node versions"
    addSequenceParams(d);  // empty: no particle
    d.params.push_back(floatParam(
        "voxelSize", 0.0, "m",
        "voxel edge of the point grid (points are bucketed per voxel); 0 = automatic, about "
        "'pointsPerVoxel' particles per occupied voxel (OpenVDB's computeVoxelSize)",
        0.0));
    d.params.push_back(intParam("pointsPerVoxel", 8, "",
                                "target particles per voxel when voxelSize is 0", 1, 1024));
    d.params.push_back(stringParam(
        "precision", "fixed16",
        "position storage: fixed16 = 16-bit offsets within the voxel (error <= voxel/65536), "
        "float = 32-bit float offsets",
        {"fixed16", "float"}));
    d.create = [] { return std::make_unique<WritePointsNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
