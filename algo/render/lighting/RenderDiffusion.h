#pragma once
/// Multiple scattering for the fast renderer: the fluence of scattered light solved once a
/// frame on a coarse lattice in the diffusion approximation,
///     −∇·(D ∇φ) + σ_a φ = Q0 − ∇·(3 D Q1),   D = 1 / (3 (σ_a + σ_s (1 − ḡ)) + R),
/// where ḡ is the phase function's mean cosine and R = |∇φ| / φ is Wilson's flux limiter,
/// which keeps the flux D |∇φ| below the fluence where light streams rather than diffuses.
/// The equation is linear and grey once R is fixed (R comes from the sun's fluence, updated
/// over a few solves; from the sky's where there is no sun), so it is solved once per light,
/// each for a unit of that light:
///   - Sun: in the δ-Eddington split of the phase function a forward peak of weight f is no
///     scattering at all, so the sun's beam fades with (1 − ω f) τ; the source is the light
///     scattered out of it, Q0 = σ_s (1 − f) exp(−(1 − ω f) τ_sun) per unit sun irradiance,
///     with its first moment Q1 = g' Q0 ω_sun (g' the remainder's asymmetry);
///   - Sky, Ground, LitGround: no source; what enters through the cloud's surface by
///     Marshak's boundary condition from a unit radiance of the sky (over the upper
///     hemisphere), of the ground, and of the sun-lit ground in the cloud's own shadow. A
///     surface face takes the sky and the ground in proportion to its view of each: first
///     the open view, then, once every light is solved, what it sees through the clear air,
///     the other clouds' scattered light of every light included (SurfaceGather.h), and
///     every light is solved again; twice, so that the second gather sees clouds that
///     already lit and shaded one another;
///   - SunGlowGround, SkyGlowGround (with a ground, in the solves after a gather): the ground
///     lit by the clouds' scattered sun and sky light, which the ground's albedo colours.
///     With them, the ground a face sees is shaded from the sky by the clouds above it and
///     lit by them, point by point; the same map of the ground lights the ground the camera
///     sees (groundAmbient).
/// The renderer scatters the fluences and fluxes of all the lights together toward the camera
/// (see RenderVolume.cc).
///
/// The lattice's cells are a few voxels wide (at most about 2 million cells); each holds the
/// mean extinction of its voxels. Empty cells lie outside the cloud: a cloud cell next to one
/// exchanges light through that face at the rate Marshak's condition gives, 2D / (h (h + 4D)).
/// The system is symmetric positive definite and solved by conjugate gradients with a Jacobi
/// preconditioner; its sums are taken in fixed blocks, so the result does not depend on the
/// thread count. See docs/rendering.md.

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include <openvdb/openvdb.h>

#include "algo/render/RenderSettings.h"
#include "algo/render/lighting/DiffuseLight.h"
#include "algo/render/lighting/GroundGrid.h"
#include "algo/render/lighting/RenderLightMap.h"

namespace cg::algo {

class RenderDiffusion {
public:
    /// The lights solved for, each per unit: sun irradiance; radiance of the sky, of the
    /// ground under the open sky (or of the horizon, without a ground), of the sun-lit ground
    /// (which the cloud's shadow dims); radiance of the clouds' sun and sky light scattered
    /// back to the ground, which the ground's albedo colours. The first kGathered are those
    /// whose scattered light the gather carries.
    enum Light { Sun, Sky, Ground, LitGround, SunGlowGround, SkyGlowGround, kLights };
    static constexpr int kGathered = LitGround + 1;

    /// The ground plane z = 0: whether there is one (the lower hemisphere is otherwise of
    /// uniform radiance, the Ground light), and whether the sun lights it.
    struct GroundPlane {
        bool present = false;
        bool sunlit = false;
    };

    /// No cloud: what lies around it everywhere.
    RenderDiffusion() = default;

    /// Solves every light for `grid` (linear transform) lit along sunMap's direction (LitGround
    /// stays 0 where the sun does not light the ground, and the glow lights without one).
    /// Stops early once `cancelled` returns true.
    RenderDiffusion(const openvdb::FloatGrid& grid, const RenderLightMap& sunMap,
                    const RenderMedium& medium, int cellVoxels, GroundPlane ground,
                    const std::function<bool()>& cancelled = {});

    /// Fluence per unit light, outside the cloud: no scattered sun light, and half the
    /// sphere's 4π for each of the sky and the ground (the open ground's).
    static constexpr double kOutside[kLights] = {
        0.0, 6.283185307179586, 6.283185307179586, 0.0, 0.0, 0.0};

    /// The lights together, light l of colour radiance[l] (the sun's in irradiance).
    DiffuseLight coloured(const RenderVec3 (&radiance)[kLights]) const;

    bool empty() const { return mPhi[Sun].empty(); }
    double cell() const { return mH; }              ///< m
    int iterations() const { return mIterations; }  ///< of the longest of the solves

private:
    /// The constructor's steps and the state they share while solving (RenderDiffusion.cc).
    class Solver;

    std::size_t index(int i, int j, int k) const
    {
        return (static_cast<std::size_t>(i) * static_cast<std::size_t>(mN[1]) +
                static_cast<std::size_t>(j)) *
                   static_cast<std::size_t>(mN[2]) +
               static_cast<std::size_t>(k);
    }

    openvdb::math::Transform mXform;  ///< the grid's: world to index space
    /// Its inverse Jacobian transpose (index-space gradient to world), held as a matrix: the
    /// map's applyIJT goes through a shared pointer copy, an atomic count per call.
    openvdb::Mat3d mGradientToWorld = openvdb::Mat3d::identity();
    openvdb::Coord mFirstVoxel;  ///< first voxel of cell (0, 0, 0)
    int mVoxels = 1;             ///< cell edge, voxels
    double mH = 0.0;             ///< cell edge, m (the smallest voxel edge × mVoxels)
    int mN[3] = {0, 0, 0};
    std::vector<float> mPhi[kLights];  ///< per light, per cell, dense
    std::vector<float> mD;             ///< diffusion coefficient per cell, m
    std::vector<float> mDrift;         ///< 3 D Q1 per cell (x, y, z): the sun part's flux source
    /// With a ground: the map of its points, and per point and light the ground's radiance
    /// per unit of that light (its sky light and the clouds' glow; no direct sun).
    GroundGrid mGround;
    std::vector<std::array<float, kLights>> mGroundLight;
    int mIterations = 0;
};

}  // namespace cg::algo
