#pragma once
/// One OpenVDB leaf (8^3 voxels) cut out of a dense float block: the voxelizers sum into dense
/// blocks that stay in cache, then keep only the leaves that hold something. Internal to
/// algo/volume.

#include <cstddef>
#include <memory>

#include <openvdb/openvdb.h>

namespace cg::algo {

/// The leaf at `leafOrigin` (index space) holding the voxels of a dense block whose voxel
/// (x, y, z) of the leaf is at first[x * xStride + y * yStride + z]: those with a value > 0
/// are active (clamped to 1 if asked), the rest are 0 and inactive. Null when no voxel is
/// active.
std::unique_ptr<openvdb::FloatTree::LeafNodeType> leafFromDense(const float* first,
                                                                std::ptrdiff_t xStride,
                                                                std::ptrdiff_t yStride,
                                                                const openvdb::Coord& leafOrigin,
                                                                bool clamp);

}  // namespace cg::algo
