#pragma once
/// The diffuse light of RenderDiffusion's lights together, per colour channel: what the fast
/// renderer looks up at every sample. Each light's fluence is solved per unit of that light;
/// the scene gives each a colour, and since the fields and their gradients are linear in
/// them, the lattice holds the sum per channel once a frame (one record of 8 floats a cell)
/// rather than four lights per lookup.

#include <cstddef>
#include <vector>

#include <openvdb/openvdb.h>

#include "algo/render/RenderSettings.h"
#include "algo/render/lighting/GroundGrid.h"
#include "algo/render/media/Phase.h"

namespace cg::algo {

/// Radiance that diffuse light of fluence φ and net flux F scatters toward `toward` (a unit
/// vector), per unit scattering. The radiance is taken as a Henyey-Greenstein lobe about F
/// with F's mean cosine k = |F| / φ: it has the fluence and flux the diffusion gives, and is
/// never negative (the P1 radiance (φ + 3 F·ω) / 4π is, wherever |F| > φ / 3). It scatters
/// through the phase function's δ-Eddington split, as the diffusion does: the peak f passes
/// it on in its own direction, HG(k), and the rest, HG(g'), turns it into HG(g' k) (HG lobes
/// convolve by multiplying their asymmetries). A sharp lobe narrowed by k instead would stay
/// so peaked (Mie's g = 0.995) that F's direction, which differs per colour channel, would
/// decide everything.
double diffuseScattered(double phi, const RenderVec3& flux, const RenderVec3& toward,
                        const DeltaEddington& split);

/// The same lobe taken apart, for light scattered toward many directions (the surface
/// gather): what does not depend on the direction, once.
struct DiffuseLobe {
    double scale = 0.0;    ///< φ / 4π
    double k2 = 0.0;       ///< k²
    RenderVec3 axis{0.0};  ///< k times F's direction
};
DiffuseLobe diffuseLobe(double phi, const RenderVec3& flux);
double diffuseScattered(const DiffuseLobe& lobe, const RenderVec3& toward,
                        const DeltaEddington& split);

class DiffuseLight {
public:
    /// Fluence and net flux F per colour channel.
    struct Sample {
        double phi[3] = {0.0, 0.0, 0.0};
        RenderVec3 flux[3] = {RenderVec3(0.0), RenderVec3(0.0), RenderVec3(0.0)};
    };

    /// Fluence `outside` everywhere, no flux: no cloud.
    explicit DiffuseLight(const RenderVec3& outside = RenderVec3(0.0)) : mOutside(outside) {}

    /// At world point p, trilinear between cell centres (the flux from the trilinear
    /// gradient, −D ∇φ, plus the sun's forward drift); outside the lattice, the fluence
    /// around the cloud and no flux.
    Sample at(const RenderVec3& p) const;

    /// The ground's radiance at p (on z = 0) from all but the direct sun: its sky light,
    /// dimmed by the clouds above it, and the light they scatter down to it, bilinear on
    /// the diffusion's map of the ground; `open` beyond it (or without one).
    RenderVec3 groundAmbient(const RenderVec3& p, const RenderVec3& open) const;

private:
    friend class RenderDiffusion;

    /// One lattice cell: what the lookup interpolates, 8 floats side by side.
    struct alignas(32) Cell {
        enum Lane { Red, Green, Blue, D, DriftX, DriftY, DriftZ, kLanes = 8 };
        /// φ per channel; the diffusion coefficient D (m); 3 D Q1 per unit sun irradiance,
        /// the sun part's own flux; an unused lane.
        float lane[kLanes];
    };

    std::size_t index(int i, int j, int k) const
    {
        return (static_cast<std::size_t>(i) * static_cast<std::size_t>(mN[1]) +
                static_cast<std::size_t>(j)) *
                   static_cast<std::size_t>(mN[2]) +
               static_cast<std::size_t>(k);
    }

    RenderVec3 mOutside;
    RenderVec3 mSun{0.0};  ///< the sun's colour, which scales the drift
    openvdb::math::Transform mXform;
    openvdb::Mat3d mGradientToWorld = openvdb::Mat3d::identity();
    openvdb::Coord mFirstVoxel;  ///< first voxel of cell (0, 0, 0)
    int mVoxels = 1;             ///< cell edge, voxels
    int mN[3] = {0, 0, 0};
    std::vector<Cell> mCells;  ///< dense
    GroundGrid mGround;
    std::vector<RenderVec3> mGroundRadiance;  ///< per point of mGround
};

}  // namespace cg::algo
