#pragma once
/// FogVolume's own stored form for the disk cache (format in FogVolumeCodec.cc). Not
/// OpenVDB's stream format: its reader trusts its input and crashes on mutated bytes, while
/// this decoder checks everything it rebuilds.

#include <openvdb/openvdb.h>

#include "core/Data.h"

namespace cg {

/// Writes `grid`. Returns false, leaving `out` partly written, when the grid is not a fog
/// volume this format holds exactly: named "density", class fog volume, background 0, a
/// linear transform (finite, affine, non-singular, voxels of 1e-3 m to 1e6 m), values finite
/// in [0, 1], voxels within +-2^30, metadata of kinds bool, int32, int64, float, double or
/// string (none under the names OpenVDB reserves), internal nodes taking at most 256 MiB
/// beyond 32 times the leaves' memory.
bool encodeFogVolume(const openvdb::FloatGrid& grid, ByteWriter& out);

/// Rebuilds what encodeFogVolume wrote: the same active voxels, values, tiles, transform and
/// metadata. Throws std::runtime_error naming "FogVolume" on bytes it would not have written
/// (any order, value, coordinate or count it never produces), before allocating the tree.
openvdb::FloatGrid::Ptr decodeFogVolume(ByteReader& in);

}  // namespace cg
