#pragma once
/// Writing one grid as a VDB file that appears whole or not at all, with the same bytes for
/// the same grid on any run and any machine.
///
/// OpenVDB stamps every file it writes with a random UUID, so two writes of the same grid
/// differ in 36 bytes. Readers use the UUID only to tell files apart (delay-loading), so we
/// replace it with one derived from the file's other bytes: a farm's frames equal a single
/// machine's, and different contents still get different UUIDs.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include <openvdb/openvdb.h>

namespace cg::formats {

/// Writes `grid` to a temporary file beside `target` (file metadata "creator" = `creator`;
/// `compression`: openvdb::io flags, OpenVDB's default when absent), sets its content UUID,
/// calls `beforeCommit` (which may throw to abandon the file) and renames it onto `target`.
/// Throws std::runtime_error naming the file on I/O failure; no partial file is left.
void writeVdbFile(const std::filesystem::path& target, const openvdb::GridBase::ConstPtr& grid,
                  const std::string& creator, std::optional<std::uint32_t> compression,
                  const std::function<void()>& beforeCommit = {});
/// The same with several grids in one file, in this order.
void writeVdbFile(const std::filesystem::path& target, const openvdb::GridCPtrVec& grids,
                  const std::string& creator, std::optional<std::uint32_t> compression,
                  const std::function<void()>& beforeCommit = {});

}  // namespace cg::formats
