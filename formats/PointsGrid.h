#pragma once
/// Cloud particles as an OpenVDB point data grid (VDB Points), the form Houdini and
/// OpenVDB's own tools read particles in. No engine includes.

#include <cstddef>
#include <cstdint>

#include <openvdb/points/PointDataGrid.h>

namespace cg::formats {

enum class PointPrecision {
    Fixed16,  ///< 16-bit fixed point within each voxel (error <= voxel size / 2^16 per axis)
    Float,    ///< 32-bit float offsets within each voxel (exact to float rounding)
};

struct PointsGridSettings {
    /// Edge of the grid's voxels, metres; 0 = chosen by OpenVDB's computeVoxelSize for about
    /// `pointsPerVoxel` particles per occupied voxel.
    double voxelSize = 0.0;
    int pointsPerVoxel = 8;
    PointPrecision precision = PointPrecision::Fixed16;
};

/// Builds a PointDataGrid named "points" holding `count` particles at `xyz` (x, y, z per
/// particle, metres) with an int32 attribute "level" and an int64 attribute "source" (the
/// types OpenVDB registers; exact for every uint8 / uint32 value). Particles keep their
/// order within each voxel but are grouped by voxel, as VDB Points stores them.
/// Throws std::invalid_argument for a non-finite position or bad settings.
openvdb::points::PointDataGrid::Ptr makeParticlePointsGrid(const float* xyz,
                                                           const std::uint8_t* levels,
                                                           const std::uint32_t* sources,
                                                           std::size_t count,
                                                           const PointsGridSettings& settings);

}  // namespace cg::formats
