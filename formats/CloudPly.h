#pragma once
/// Cloud particles as a binary little-endian PLY point cloud:
///
///   ply / format binary_little_endian 1.0 / comment CloudGraph ... / element vertex N /
///   property float x / property float y / property float z / property uchar level /
///   property uint source / end_header
///
/// then N records of 17 bytes (positions in metres), little-endian on any host.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

namespace cg::formats {

/// Throws std::runtime_error naming the file when it cannot be written.
void writeCloudPly(const std::filesystem::path& path, std::size_t count, const float* positions,
                   const std::uint8_t* levels, const std::uint32_t* sources,
                   const std::string& comment = "", const std::function<void()>& poll = {});

}  // namespace cg::formats
