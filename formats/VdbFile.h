#pragma once
/// Reading a fog volume from an OpenVDB file written by another program (Houdini, Blender,
/// EmberGen) or by WriteVDB. What is accepted, and what is refused with a FormatError whose
/// `where` is the file and whose message names the grid:
///
/// - the file: a regular file of at most `maxBytes` bytes that OpenVDB opens;
/// - the grid: named `gridName` (a missing grid is refused with the names and value types of
///   the grids the file has); values float (also stored as half floats) or double (converted
///   to float); vector, integer, bool, point and other grids are refused;
/// - its class: fog volume or unknown; a level set (signed distances) or a staggered grid is
///   refused, and so is a grid whose background is not 0 (a level set saved without its class);
/// - its transform: linear (affine: no frustum), finite, voxels larger than 0 on every axis;
/// - its size: the memory and active voxel count the file records for the grid (OpenVDB
///   writes them as the grid's "file_mem_bytes" and "file_voxel_count" metadata) within
///   `maxBytes` (4 bytes a voxel when only the count is recorded), checked before the tree is
///   read, and the tree's memory again once it is;
/// - its values: finite everywhere (active or not, voxels and tiles); NaN or infinity is
///   refused with the voxel's coordinates. Negative values (an advected simulation's ringing)
///   are set to 0. Values above 1 are kept: the renderer scales density by its extinction.
///
/// The grid returned is a fog volume as the rest of CloudGraph knows it: named "density",
/// class fog volume, stored as full floats, with the file's own metadata kept except the names
/// OpenVDB reserves ("file_*", "creator", "is_saved_as_half_float", ...) and kinds other than
/// bool, int32, int64, float, double and string.
///
/// Before OpenVDB reads a byte, the file's header, its grid descriptors (names, types,
/// offsets) and the grid's metadata and transform name are walked here with every length,
/// count and offset checked against the file, so a truncated file is refused by its offsets
/// and no string or table OpenVDB allocates is larger than the file. OpenVDB then reads the
/// grid from a stream holding that grid alone that throws on a read past its end, so a lying
/// count inside the tree ends in an error rather than in reading garbage. The tree's own
/// compressed-block sizes are still OpenVDB's to trust: it allocates a block's stated size
/// before reading it, so a damaged size can ask for gigabytes; the std::bad_alloc that follows
/// is refused as a damaged file (the vdb_reader fuzz target exercises this).

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <openvdb/openvdb.h>

namespace cg::formats {

/// What a VDB file records for one grid, read without its voxels.
struct VdbGridSummary {
    std::string name;
    std::string valueType;           ///< "float", "double", "vec3s", ...
    std::string gridClass;           ///< "fog volume", "level set", "unknown", ...
    bool halfFloat = false;          ///< stored as 16-bit floats
    std::uint64_t activeVoxels = 0;  ///< as the file records it (0 when it does not)
    std::uint64_t memoryBytes = 0;   ///< the tree's memory as recorded (0 when not recorded)
    /// The active voxels' bounding box as recorded ("file_bbox_min", "file_bbox_max"), when
    /// recorded and not empty; nothing checks it against the voxels.
    std::optional<openvdb::CoordBBox> activeBox;
};

/// The grids of the VDB file `path`, in file order, from its header and grid metadata only.
/// Throws FormatError when the file cannot be read as a VDB file.
std::vector<VdbGridSummary> listVdbGrids(const std::filesystem::path& path, std::uint64_t maxBytes);

/// Checks everything readVdbFogVolume checks before reading the voxels: the file, the grid's
/// presence, value type, class, transform, recorded size and background (read from the start
/// of the tree). Throws FormatError.
VdbGridSummary inspectVdbFogVolume(const std::filesystem::path& path, const std::string& gridName,
                                   std::uint64_t maxBytes);

/// Reads grid `gridName` of `path` as a fog volume (see above). Throws FormatError.
openvdb::FloatGrid::Ptr readVdbFogVolume(const std::filesystem::path& path,
                                         const std::string& gridName, std::uint64_t maxBytes);

}  // namespace cg::formats
