#pragma once
/// OpenVDB stamps every file it writes with a random UUID, so two writes of the same grids
/// differ in 36 bytes. Readers use the UUID only to tell files apart (delay-loading), so
/// we replace it with one derived from the file's other bytes: the same grids give the same
/// file, bit for bit, on any run and any machine (a farm's frames equal a single machine's),
/// and different contents still get different UUIDs.

#include <filesystem>

namespace cg::formats {

/// Rewrites, in place, the UUID of the VDB file at `path` (one just written by
/// openvdb::io::File, not yet renamed into place). Throws std::runtime_error naming the
/// file when it cannot be read or is not a VDB file.
void setContentUuid(const std::filesystem::path& path);

}  // namespace cg::formats
