#pragma once
/// Cloud particles as an OpenVDB point data grid (VDB Points), the form Houdini and
/// OpenVDB's own tools read particles in. The grid is built from particles handed over in
/// chunks, as a frame streams from the mapper, so nothing frame-sized exists but the grid
/// itself. No engine includes.

#include <cstddef>
#include <cstdint>
#include <functional>

#include <openvdb/points/PointDataGrid.h>

namespace cg::formats {

enum class PointPrecision {
    Fixed16,  ///< 16-bit fixed point within each voxel (error <= voxel size / 2^16 per axis)
    Float,    ///< 32-bit float offsets within each voxel (exact to float rounding)
};

struct PointsGridSettings {
    /// Edge of the grid's voxels, metres; 0 = chosen as OpenVDB's computeVoxelSize chooses it
    /// (the same value), for about `pointsPerVoxel` particles per occupied voxel.
    double voxelSize = 0.0;
    int pointsPerVoxel = 8;
    PointPrecision precision = PointPrecision::Fixed16;
};

/// Particles first .. first + count - 1 of a frame: x, y, z per particle (metres), and their
/// levels and source ids when the pass asked for them (null otherwise).
struct ParticleChunk {
    std::uint64_t first = 0;
    std::size_t count = 0;
    const float* xyz = nullptr;
    const std::uint8_t* levels = nullptr;
    const std::uint32_t* sources = nullptr;
};

/// Hands every particle of a frame to `consume` once, in chunks, possibly from several
/// threads at once and in any order, but the same chunks (first, count) on every call;
/// levels and sources come when `attributes` is true.
using ParticleChunks =
    std::function<void(const std::function<void(const ParticleChunk&)>& consume, bool attributes)>;

/// Builds a PointDataGrid named "points" with an int32 attribute "level" and an int64
/// attribute "source" (the types OpenVDB registers; exact for every uint8 / uint32 value),
/// equal value for value to what OpenVDB's createPointIndexGrid + createPointDataGrid +
/// populateAttribute make of the same particles: grouped by voxel, in particle order within
/// each voxel. It passes over the chunks a few times (a survey, the automatic voxel size's
/// iterations, a count per voxel, the fill) and keeps per voxel only counts.
class ParticlePointsGridBuilder {
public:
    /// Surveys the particles: their count and bounds. Throws std::invalid_argument for a
    /// non-finite position (naming the particle), 2^32 particles or more, or bad settings.
    ParticlePointsGridBuilder(ParticleChunks chunks, const PointsGridSettings& settings);

    std::uint64_t count() const { return mCount; }
    openvdb::points::PointDataGrid::Ptr build() const;

private:
    double voxelSize() const;
    std::size_t occupiedVoxels(float voxelSize) const;

    ParticleChunks mChunks;
    PointsGridSettings mSettings;
    std::uint64_t mCount = 0;
    openvdb::Vec3f mMin, mMax;  ///< bounds of the positions
};

/// The same from whole arrays: `count` particles at `xyz` with their levels and sources.
openvdb::points::PointDataGrid::Ptr makeParticlePointsGrid(const float* xyz,
                                                           const std::uint8_t* levels,
                                                           const std::uint32_t* sources,
                                                           std::size_t count,
                                                           const PointsGridSettings& settings);

}  // namespace cg::formats
