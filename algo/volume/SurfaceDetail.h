#pragma once
/// Sub-particle detail that sticks to the cloud: Perlin-Worley noise erodes the density near
/// the cloud's surface, evaluated in each copy's own coordinates (x minus the copy's origin,
/// i.e. R P_f of Eq. 10 plus the copy's drift), so a copy that the mapper moves carries its
/// detail along instead of moving through a noise fixed in space.
///
/// Only the surface shell is touched: voxels whose splatted density v lies strictly between
/// 0 and 1 (where the particles' smooth kernels fall off; clamped interiors are 1). There
/// the erosion e = amplitude (1 - n), n the noise in [0, 1] (high inside a billow), remaps
/// v to (v - e) / (1 - e), the erosion production cloud shaders use (Schneider 2015): the
/// creases between billows are cut into the soft edge, the billows keep their density, and
/// voxels eroded to nothing are switched off, so the grid only gets sparser.
///
/// Deterministic for any thread count: each voxel depends only on its own value, its
/// position and the copy origin field. No engine includes.

#include <cstddef>
#include <cstdint>
#include <functional>

#include <openvdb/openvdb.h>

#include "algo/volume/CopyOriginField.h"

namespace cg::algo {

struct SurfaceDetailSettings {
    /// Largest erosion e, in density (0: no detail, the grid is left untouched).
    double amplitude = 0.0;
    /// Noise cycles per metre of the first octave (> 0).
    double frequency = 1.0 / 100.0;
    /// Octaves of the Perlin-Worley fractal sum, each twice the frequency and half the weight.
    int octaves = 2;
};

/// The particles whose splats made a grid, with the copy each moves with: particle i at
/// xyz[3 i ...] belongs to the copy whose origin is copyOrigins[3 sources[i] ...]. Without
/// copy origins (copyOrigins null), the noise is evaluated in world coordinates.
struct DetailParticles {
    const float* xyz = nullptr;
    const std::uint32_t* sources = nullptr;
    std::size_t count = 0;
    const float* copyOrigins = nullptr;
    std::size_t copyCount = 0;
};

/// Erodes the shell of `grid` (a fog volume made by voxelizeParticles from `particles` with
/// splat radius `radius` metres) in place. Throws std::invalid_argument for bad settings or
/// a particle whose source has no copy origin. `checkCancelled` (optional) is called between
/// phases and may throw.
void erodeSurface(openvdb::FloatGrid& grid, const DetailParticles& particles, double radius,
                  const SurfaceDetailSettings& settings,
                  const std::function<void()>& checkCancelled = {});

/// The cell edge of the copy origin field for splats of radius `radius` on voxels of
/// `voxelSize` (metres): at least 2R, so every voxel a splat reaches has its particle's cell
/// as a corner.
double copyOriginCellSize(double radius, double voxelSize);

/// The same erosion with the copy origin field already built (cells of copyOriginCellSize),
/// as a streaming voxelizer builds it while splatting; null: world coordinates.
void erodeSurface(openvdb::FloatGrid& grid, const CopyOriginField* field,
                  const SurfaceDetailSettings& settings,
                  const std::function<void()>& checkCancelled = {});

}  // namespace cg::algo
