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

namespace cg::algo {

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
};

}  // namespace cg::algo
