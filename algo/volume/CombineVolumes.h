#pragma once
/// Two fog volumes on the same voxel grid combined voxel by voxel. No engine includes.

#include <stdexcept>

#include <openvdb/openvdb.h>

namespace cg::algo {

enum class CombineMode { Max, Sum };

/// Parses "max" or "sum"; throws std::invalid_argument otherwise.
CombineMode combineModeFromName(const std::string& name);

/// A new fog volume named "density" with a's metadata: per voxel the larger density (Max) or
/// the sum clamped to 1 (Sum), by openvdb::tools::compMax / compSum on copies, so the inputs
/// are untouched. Throws std::invalid_argument when the transforms differ: voxel (i, j, k)
/// must be the same place in both, or the combination means nothing.
openvdb::FloatGrid::Ptr combineFogVolumes(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b,
                                          CombineMode mode);

}  // namespace cg::algo
