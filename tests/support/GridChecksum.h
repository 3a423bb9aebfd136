#pragma once
/// A grid's exact content as one number, for tests that pin a grid or compare two bit for bit.

#include <cstdint>

#include <openvdb/openvdb.h>

namespace cg::test {

/// FNV-1a over every active voxel's coordinate and value bits, in the tree's (sorted) order.
std::uint64_t gridChecksum(const openvdb::FloatGrid& grid);

}  // namespace cg::test
