#pragma once
/// Particles to a sparse OpenVDB fog volume (Sec. 6.3: "volume data with alpha values").
///
/// Each particle splats a radial kernel of radius R (metres) onto the centres of the voxels
/// around it; contributions add up. Index space is OpenVDB's: voxel (i, j, k) has its centre at
/// (i, j, k) * voxelSize in metres. Only leaves (8^3 voxels) that some particle touches are
/// allocated, so memory follows the occupied space, never the bounding box.
///
/// Deterministic for any thread count: particles are binned into the bricks (4^3 leaves) they
/// touch, ordered by (brick, particle index), and each brick sums its particles in ascending
/// index order within one task. No engine includes.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>

#include <openvdb/openvdb.h>

namespace cg::algo {

/// The radial profile a particle splats; r is the distance from the particle, R its radius.
enum class VoxelKernel {
    /// w(r) = (1 - r^2/R^2)^3 for r < R, else 0: smooth (C^2 at r = R), peak 1 at the centre.
    /// Integral over space: 64 pi R^3 / 315.
    Smooth,
    /// w(r) = 1 for r < R, else 0: a hard ball. Integral over space: 4 pi R^3 / 3.
    Sphere,
    /// w(r) = exp(-r^2 / (2 sigma^2)), sigma = 0.3435 R: the smooth kernel's peak and integral,
    /// splatted by a trilinear deposit and separable blur passes, at a cost that does not grow
    /// with R^3 (algo/volume/GaussianSplat.h). Integral: 64 pi R^3 / 315.
    Gaussian,
};

/// Parses "smooth", "sphere" or "gaussian"; throws std::invalid_argument otherwise.
VoxelKernel voxelKernelFromName(const std::string& name);

/// The kernel's integral over all space, in m^3 for R in metres: what one particle of density
/// 1 contributes to sum(voxel value) * voxelSize^3 in the continuum limit.
double kernelIntegral(VoxelKernel kernel, double radius);

struct VoxelizeSettings {
    double voxelSize = 4.0;  ///< voxel edge, metres (> 0)
    double radius = 8.0;     ///< kernel radius R, metres (> 0, <= 32 voxels)
    VoxelKernel kernel = VoxelKernel::Smooth;
    /// What one particle adds at its own centre (density is dimensionless, fog volume
    /// convention: 1 = fully dense). A voxel at distance r gets density * w(r).
    double density = 0.25;
    bool clamp = true;  ///< clamp summed values to [0, 1] (fog volume)
    /// Refuse (VoxelizeTooLarge) when the estimated peak memory exceeds this; 0: no limit.
    std::uint64_t maxBytes = 0;
};

/// Throws std::invalid_argument unless the voxel size is > 0, the radius in (0, 32 voxels]
/// and the density finite and >= 0.
void checkVoxelizeSettings(const VoxelizeSettings& settings);

/// The splat would need more memory than VoxelizeSettings::maxBytes: bad settings (voxels
/// too small for the particles' spacing, or too many particles), said before any work.
class VoxelizeTooLarge : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

/// An upper bound of the voxelizer's peak memory for `count` particles whose index-space
/// bounds (positions / voxel size) span `extentVoxels` per axis: the binned entries and
/// their sort scratch, plus every leaf that the splats or the bounds allow, whichever is less.
std::uint64_t voxelizeMemoryBound(std::size_t count, const double extentVoxels[3],
                                  double radiusVoxels);

/// Voxelizes `count` particles whose positions are `xyz` (x, y, z per particle, metres) into a
/// FloatGrid named "density" of class GRID_FOG_VOLUME with a linear transform of the voxel
/// size, background 0. A voxel is active when its value is > 0. `checkCancelled` (optional)
/// is called between phases on the calling thread and may throw. Throws
/// std::invalid_argument for bad settings, non-finite positions or coordinates beyond
/// +-2^28 voxels.
openvdb::FloatGrid::Ptr voxelizeParticles(const float* xyz, std::size_t count,
                                          const VoxelizeSettings& settings,
                                          const std::function<void()>& checkCancelled = {});

enum class VoxelFilter { None, Mean, Gaussian, Median };

/// Parses "none", "mean", "gaussian" or "median"; throws std::invalid_argument otherwise.
VoxelFilter voxelFilterFromName(const std::string& name);

/// Smooths the active voxels of `grid` in place with openvdb::tools::Filter: `iterations`
/// passes of a (2 * width + 1)^3 mean, Gaussian or median stencil (width in voxels). The
/// topology is kept (no dilation), so values stay in the range they had; deterministic.
void filterVolume(openvdb::FloatGrid& grid, VoxelFilter filter, int width, int iterations);

}  // namespace cg::algo
