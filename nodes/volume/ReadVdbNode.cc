// ReadVDB: a fog volume from an OpenVDB file (formats/VdbFile.h says what is accepted).

#include <memory>
#include <string>

#include "algo/render/media/RenderOccupancy.h"
#include "core/Error.h"
#include "core/Hash.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "formats/FileHash.h"
#include "formats/FormatError.h"
#include "formats/VdbFile.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/FogVolume.h"
#include "nodes/volume/VolumeNodes.h"
#include "util/SystemMemory.h"

namespace cg {

namespace {

class ReadVdbNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        const std::string& file = ctx.params().getString("file");
        if (file.empty()) throw InputError(ctx.nodeId(), "ReadVDB: parameter 'file' is empty");
        openvdb::FloatGrid::Ptr grid = formats::readVdbFogVolume(
            file, ctx.params().getString("grid"), util::nodeAllocationLimitBytes());
        ctx.setOutput("volume", std::make_shared<FogVolumeData>(std::move(grid)));
    }
};

std::string boxText(const openvdb::CoordBBox& box)
{
    const auto coord = [](const openvdb::Coord& c) {
        return "(" + std::to_string(c.x()) + ", " + std::to_string(c.y()) + ", " +
               std::to_string(c.z()) + ")";
    };
    return "its active voxels span " + coord(box.min()) + " to " + coord(box.max());
}

}  // namespace

void checkReadVdbVoxels(const ParamSet& params, const std::string& nodeLocation,
                        std::uint64_t maxBytes)
{
    const std::string& file = params.getString("file");
    if (file.empty()) return;  // refused when the graph loads
    const std::string& grid = params.getString("grid");
    try {
        const openvdb::FloatGrid::Ptr volume = formats::readVdbFogVolume(file, grid, maxBytes);
        // The box the voxels span, where the file recorded none (or a false one).
        const openvdb::CoordBBox box = volume->evalActiveVoxelBoundingBox();
        if (const std::string problem = algo::RenderOccupancy::domainProblem(box); !problem.empty())
            throw formats::FormatError(file,
                                       "grid '" + grid + "': " + boxText(box) + ": " + problem);
    } catch (const formats::FormatError& e) {
        throw InputError(nodeLocation + "/params/file", e.what());
    }
}

void registerReadVdbNode(Registry& registry)
{
    NodeDecl d;
    d.type = "ReadVDB";
    d.category = "volume";
    d.doc =
        "Reads a fog volume from an OpenVDB file written by Houdini, Blender, EmberGen or "
        "WriteVDB, so that the Renderer can light it. Accepted: a grid of float values (also "
        "stored as half floats) or double values (converted to float), of class fog volume or "
        "unknown, background 0, a linear transform (its voxel size is taken as metres). Values "
        "above 1 are kept (the renderer multiplies density by its extinction); negative values "
        "are set to 0; NaN or infinity is refused. Refused with the file and grid named (exit "
        "2): a missing grid (the message lists the file's grids), a level set, a vector or "
        "integer grid, a frustum transform, a damaged or truncated file, a grid whose "
        "recorded size exceeds the memory one node may take, and one whose recorded bounding "
        "box spans more than the Renderer can hold (2^27 blocks of 8^3 voxels), all checked "
        "before its voxels are read; `validate` also reads the voxels. The output is named "
        "'density', class fog volume, with the file's plain metadata "
        "(bool, integer, float, string). The key holds the file's content, not its path or time "
        "stamp.";
    d.outputs = {port("volume", "FogVolume", "the grid, as a fog volume named 'density'")};
    d.params = {
        inputFileParam("file", "",
                       "path of the .vdb file (a relative path is found beside the graph file)"),
        stringParam("grid", "density",
                    "name of the grid to read (Houdini and Blender name a fog volume 'density')"),
    };
    d.hashExtra = [](const ParamSet& p, Hasher& h) {
        // The file's content, not its path (the engine leaves input-file parameters out), so
        // a copied or moved file is still a cache hit. An unreadable file fails at cook time
        // with its reason; until then its path stands in for the content.
        const std::string& file = p.getString("file");
        try {
            h.str("content").u64(
                formats::fileContentHash(file, util::nodeAllocationLimitBytes(), "VDB file"));
        } catch (const formats::FormatError&) {
            h.str("unreadable").str(file);
        }
    };
    d.validate = [](const ParamSet& p, const ParamChecker& check) {
        // The file's header and the grid's metadata, so that `validate` refuses a missing
        // grid, a level set or an absurd size; the voxels are checked when they are read.
        if (p.getString("grid").empty()) check.fail("grid", "the grid name is empty");
        const std::string& file = p.getString("file");
        if (file.empty()) return;
        const std::string& grid = p.getString("grid");
        try {
            const formats::VdbGridSummary s =
                formats::inspectVdbFogVolume(file, grid, check.allocationLimitBytes);
            // The Renderer refuses a domain its occupancy grid cannot hold; the box the file
            // records shows that now rather than after the voxels are read.
            if (s.activeBox)
                if (const std::string problem = algo::RenderOccupancy::domainProblem(*s.activeBox);
                    !problem.empty())
                    throw formats::FormatError(
                        file, "grid '" + grid + "': " + boxText(*s.activeBox) + ": " + problem);
        } catch (const formats::FormatError& e) {
            check.fail("file", e.what());
        }
    };
    d.create = [] { return std::make_unique<ReadVdbNode>(); };
    // The contract test has no file to give it; tests/nodes/test_read_vdb_node.cc covers it.
    d.quickParams = {{"__skipCook", "true"}};
    registry.addNode(std::move(d));
}

}  // namespace cg
