#pragma once
/// Exports frames of a primitive set as binary PLY point clouds (one file per frame), through
/// the PLY writer of PlyWriter.h: x y z are the positions (m, from the cloud origin), id the
/// stable cloud-particle id; vz, temperature and home_cell are 0 and state is 1 (condensed).

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace cg::formats {

/// Writes frame s (positions = 3 count floats) to `path`.
void writePrimitiveFramePly(const std::filesystem::path& path, const float* positions,
                            std::uint32_t count, int frame, const std::function<void()>& poll = {});

/// `pattern` with its run of '#' replaced by the zero-padded frame number (4 digits when there
/// is no '#': "name.ply" becomes "name.0007.ply").
std::filesystem::path primitiveFramePath(const std::filesystem::path& pattern, int frame);

}  // namespace cg::formats
