#pragma once
/// The Gaussian kernel of the voxelizer, splatted at a cost that does not grow with the cube
/// of the radius: each particle adds its cloud-in-cell (trilinear) weights to the 8 voxels
/// around it, and the deposit is then blurred by three separable 1D Gaussian passes. A
/// particle costs 8 adds, whatever its radius; the blur costs about 3 (2 T + 1) operations a
/// voxel near the particles, T the number of taps a side.
///
/// The kernel is w(r) = exp(-r^2 / (2 sigma^2)) with sigma = (315 / (64 pi))^(1/3) R /
/// sqrt(2 pi) = 0.3435 R: the same peak (density) and the same integral (64 pi R^3 / 315) as
/// the smooth kernel (1 - r^2/R^2)^3 of radius R. The cloud-in-cell deposit blurs by a tent
/// of variance 1/6 voxel^2 per axis, so the passes blur by the rest, sigma_b^2 = sigma^2 -
/// 1/6, with taps to |d| <= ceil(3 sigma_b) voxels; under about R = 1.2 voxels nothing is
/// left for the passes and the kernel is the trilinear deposit alone.
///
/// Deterministic for any thread count and any order of `add` calls: the deposit sums
/// integer weights (each axis's cloud-in-cell weight in units of 2^-10, their product in units
/// of 2^-30, so a particle deposits exactly 1), which add associatively, and
/// the blur reads a fixed neighbourhood. That is what lets particles stream in chunks from
/// several threads without a frame-sized array. No engine includes.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>

#include <openvdb/openvdb.h>

#include "algo/volume/Voxelize.h"

namespace cg::algo {

/// sigma of the Gaussian kernel of radius R, in the units of R (see above).
double gaussianKernelSigma(double radius);

class GaussianSplatter {
public:
    /// Throws std::invalid_argument for bad settings (as voxelizeParticles).
    explicit GaussianSplatter(const VoxelizeSettings& settings);
    ~GaussianSplatter();
    GaussianSplatter(const GaussianSplatter&) = delete;
    GaussianSplatter& operator=(const GaussianSplatter&) = delete;

    /// Deposits `count` particles (x, y, z per particle, metres). Safe to call from several
    /// threads at once. Throws std::invalid_argument for a position that is not finite or
    /// lies beyond 2^20 voxels, VoxelizeTooLarge when the deposit would pass
    /// settings.maxBytes.
    void add(const float* xyz, std::size_t count);

    /// Particles deposited so far.
    std::uint64_t count() const { return mCount.load(); }

    /// Blurs the deposit into a FloatGrid named "density", class fog volume, transform of the
    /// voxel size, background 0; a voxel is active when its value is > 0 (clamped to 1 when
    /// settings.clamp). Call once, after every add has returned. `checkCancelled` (optional)
    /// is called between phases on the calling thread and may throw.
    openvdb::FloatGrid::Ptr finish(const std::function<void()>& checkCancelled = {});

private:
    struct Deposit;
    VoxelizeSettings mSettings;
    std::unique_ptr<Deposit> mDeposit;
    std::atomic<std::uint64_t> mCount{0};
};

}  // namespace cg::algo
