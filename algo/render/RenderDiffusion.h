#pragma once
/// Multiple scattering for the fast renderer: the fluence of scattered light solved once a
/// frame on a coarse lattice in the diffusion approximation,
///     −∇·(D ∇φ) + σ_a φ = S,   D = 1 / (3 (σ_a + σ_s (1 − ḡ))),
/// where ḡ is the phase function's mean cosine. Two unit problems are solved, since the
/// equation is linear and grey: φ_sun, whose source is the sun light scattered once,
/// S = σ_s exp(−τ_sun) per unit sun irradiance, and φ_env, driven by a unit isotropic fluence
/// at the cloud's surface (Marshak's boundary condition) with no source. Then the fluence of
/// scattered light is E_sun φ_sun + Φ_env φ_env, with Φ_env the fluence of the sky and ground
/// around the cloud, and a camera sample adds σ_s φ / (4π) to its single scattering.
///
/// The lattice's cells are a few voxels wide (at most about 2 million cells); each holds the
/// mean extinction of its voxels. Empty cells lie outside the cloud: a cloud cell next to one
/// loses light through that face at the rate Marshak's condition gives, 2D / (h (h + 4D)).
/// The system is symmetric positive definite and solved by conjugate gradients with a Jacobi
/// preconditioner; its sums are taken in fixed blocks, so the result does not depend on the
/// thread count. See docs/rendering.md.

#include <cstddef>
#include <functional>
#include <vector>

#include <openvdb/openvdb.h>

#include "algo/render/RenderLightMap.h"
#include "algo/render/RenderSettings.h"

namespace cg::algo {

class RenderDiffusion {
public:
    /// No cloud: φ_sun = 0 and φ_env = 1 everywhere.
    RenderDiffusion() = default;

    /// Solves both problems for `grid` (linear transform) lit along sunMap's direction.
    /// Stops early once `cancelled` returns true.
    RenderDiffusion(const openvdb::FloatGrid& grid, const RenderLightMap& sunMap,
                    const RenderMedium& medium, int cellVoxels,
                    const std::function<bool()>& cancelled = {});

    struct Fluence {
        double sun = 0.0;  ///< per unit sun irradiance
        double env = 1.0;  ///< per unit fluence of the surroundings
        RenderVec3 sunFlux{0.0, 0.0, 0.0};  ///< net flux −D ∇φ_sun, per unit sun irradiance
        RenderVec3 envFlux{0.0, 0.0, 0.0};  ///< −D ∇φ_env, per unit fluence around
    };

    /// Both fluences and their net fluxes at world point p, trilinear between cell centres
    /// (the fluxes from the trilinear gradient); outside the lattice, what lies around the
    /// cloud: no scattered sun light, the surroundings' fluence, no net flux.
    Fluence at(const RenderVec3& p) const;

    bool empty() const { return mSun.empty(); }
    double cell() const { return mH; }  ///< m
    int iterations() const { return mIterations; }  ///< of the larger of the two solves

private:
    std::size_t index(int i, int j, int k) const
    {
        return (static_cast<std::size_t>(i) * static_cast<std::size_t>(mN[1]) +
                static_cast<std::size_t>(j)) * static_cast<std::size_t>(mN[2]) +
               static_cast<std::size_t>(k);
    }

    openvdb::math::Transform mXform;  ///< the grid's: world to index space
    openvdb::Coord mFirstVoxel;       ///< first voxel of cell (0, 0, 0)
    int mVoxels = 1;                  ///< cell edge, voxels
    double mH = 0.0;                  ///< cell edge, m (the smallest voxel edge × mVoxels)
    int mN[3] = {0, 0, 0};
    std::vector<float> mSun, mEnv;  ///< per cell, dense
    std::vector<float> mD;          ///< diffusion coefficient per cell, m
    int mIterations = 0;
};

}  // namespace cg::algo
