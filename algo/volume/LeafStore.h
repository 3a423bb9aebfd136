#pragma once
/// Writing a fog volume's voxel from a pass over a leaf's active voxels: a value above 0 is
/// stored, anything else becomes the background, inactive, so a pass only ever makes the
/// grid sparser where it takes density away (what a fog volume's active voxels mean: > 0).

#include <openvdb/openvdb.h>

namespace cg::algo {

template <typename LeafT>
inline void storeOrSwitchOff(LeafT& leaf, float* values, openvdb::Index n, float value)
{
    if (value > 0.0f) {
        values[n] = value;
    } else {
        values[n] = 0.0f;
        leaf.setValueOff(n);
    }
}

}  // namespace cg::algo
