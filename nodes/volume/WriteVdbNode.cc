// WriteVDB: a fog volume as an OpenVDB file per frame, written atomically.

#include <memory>
#include <string>

#include <openvdb/io/File.h>

#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "formats/VdbFileWriter.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/FogVolume.h"
#include "nodes/data/VelocityVolume.h"
#include "nodes/io/WriterSupport.h"
#include "nodes/volume/VolumeNodes.h"

namespace cg {

namespace {

/// OpenVDB compression flags for a "compression" choice. Debian's OpenVDB 10 is built with
/// Blosc; "auto" falls back to zip on a build without it (checked at run time).
std::uint32_t compressionFlags(const std::string& choice, const std::string& nodeId)
{
    const bool blosc = openvdb::io::Archive::hasBloscCompression();
    if (choice == "none") return openvdb::io::COMPRESS_NONE;
    if (choice == "zip") return openvdb::io::COMPRESS_ACTIVE_MASK | openvdb::io::COMPRESS_ZIP;
    if (choice == "blosc" && !blosc)
        throw InputError(nodeId, "this OpenVDB build has no Blosc compression; use zip or auto");
    return openvdb::io::COMPRESS_ACTIVE_MASK |
           (blosc ? openvdb::io::COMPRESS_BLOSC : openvdb::io::COMPRESS_ZIP);
}

/// The velocity grid to write beside `density`, which it must share a transform with.
openvdb::GridBase::ConstPtr velocityGrid(const VelocityVolumeData& velocity,
                                         const openvdb::FloatGrid& density, bool half,
                                         const std::string& nodeId)
{
    if (velocity.grid->transform() != density.transform())
        throw InputError(nodeId + "/inputs/velocity",
                         "the velocity grid is not on the volume's transform (make it from "
                         "the same volume with CloudVelocity)");
    openvdb::Vec3fGrid::Ptr grid = openvdb::ConstPtrCast<openvdb::Vec3fGrid>(velocity.grid)->copy();
    grid->setName("vel");
    grid->setSaveFloatAsHalf(half);
    return grid;
}

class WriteVdbNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const auto volume = ctx.input<FogVolumeData>("volume");
        if (!writesSequenceFrame(ctx, /*empty=*/!volume->grid->cbeginValueOn())) return;
        const std::uint32_t flags =
            compressionFlags(ctx.params().getString("compression"), ctx.nodeId());
        // A shallow copy shares the (immutable) tree; only its save flag differs.
        openvdb::FloatGrid::Ptr grid =
            openvdb::ConstPtrCast<openvdb::FloatGrid>(volume->grid)->copy();
        const bool half = ctx.params().getBool("halfFloat");
        grid->setSaveFloatAsHalf(half);
        openvdb::GridCPtrVec grids{grid};
        if (const auto velocity = ctx.input<VelocityVolumeData>("velocity"))
            grids.push_back(velocityGrid(*velocity, *grid, half, ctx.nodeId()));

        const std::filesystem::path path = ctx.outputPath("file");
        formats::writeVdbFile(path, grids, "CloudGraph WriteVDB", flags,
                              [&] { ctx.checkCancelled(); });
        ctx.setOutput("files", std::make_shared<TextData>(path.string()));
    }
};

}  // namespace

void registerWriteVdbNode(Registry& registry)
{
    NodeDecl d = writerDecl(
        "WriteVDB",
        "Writes a fog volume as an OpenVDB file (one grid, 'density'), readable by vdb_print, "
        "vdb_render, Houdini and Blender. #### in the name becomes the frame number; the file "
        "is written beside the target and renamed, so it appears whole or not at all. Writes "
        "frames firstFrame, firstFrame + every, ... and, with skipEmpty, only those whose grid "
        "has an active voxel: a cloud that forms at frame 51 of a run with every = 1 gives "
        "density.0051.vdb, density.0052.vdb, ..., a numbered sequence that Blender imports "
        "as one (it needs consecutive numbers: every = 1, and skipEmpty off if the cloud can "
        "vanish mid-run). With a velocity (CloudVelocity), the file also holds the Vec3f grid "
        "'vel' in m/s, which Houdini reads as velocity and Blender as the volume's velocity "
        "grid (motion blur).",
        port("volume", "FogVolume", "the volume to write"), "density.####.vdb");
    d.inputs.push_back(port("velocity", "VelocityVolume",
                            "optional: the volume's velocity, written as the grid 'vel'", true));
    d.version = 2;         // each version's change: CHANGES.md, "Node versions"
    addSequenceParams(d);  // empty: a grid without active voxels
    d.params.push_back(boolParam("halfFloat", false,
                                 "store values as 16-bit half floats (half the size, ~3 digits)"));
    d.params.push_back(stringParam(
        "compression", "auto",
        "auto = blosc when this OpenVDB has it (Debian's does), else zip; none = uncompressed",
        {"auto", "blosc", "zip", "none"}));
    d.create = [] { return std::make_unique<WriteVdbNode>(); };
    registry.addNode(std::move(d));
}

}  // namespace cg
