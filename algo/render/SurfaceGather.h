#pragma once
/// What each surface face of the diffusion lattice's clouds sees through the clear air: the
/// sky and the ground, dimmed by the clouds in between, and the light those clouds scatter
/// toward it. RenderDiffusion lets this in through the face (Marshak's condition) instead of
/// the open sky and ground, so a cloud in the shade of another, or deep in a crevice, gets
/// the sky it sees and the light its sunlit neighbours send it.
///
/// Along a direction v the lattice is swept slice by slice from the far side (a discrete-
/// ordinates sweep, the upstream value interpolated bilinearly in the slice before): the
/// transmittance T toward v and, per unit light, the radiance E the clouds scatter back
/// along −v, E = ∫ σ_t J exp(−τ) ds with J the cell's source radiance (its scattered light,
/// taken as isotropic). Directions are points of a Fibonacci sphere (about equal solid
/// angles); a face takes the cosine-weighted means of T and E over the directions in its
/// outward hemisphere, above and below the horizon apart. The directions are swept one after
/// another and each slice's cells in parallel, so the result does not depend on the thread
/// count.

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include <openvdb/openvdb.h>

#include "algo/render/RenderSettings.h"

namespace cg::algo {

/// The lattice a gather runs on: a dense box of cells, index (i n1 + j) n2 + k.
struct GatherLattice {
    static constexpr int kUnits = 4;  ///< the lights whose scattered light is gathered
    int n[3] = {0, 0, 0};
    std::vector<double> extinction;                 ///< σ_t per cell, 1/m (0: clear air)
    std::vector<std::array<float, kUnits>> source;  ///< J per cell and unit light (radiance)
    /// World direction (per metre) to cells: a displacement d (m) moves cellsPerMetre * d.
    openvdb::Mat3d cellsPerMetre = openvdb::Mat3d::identity();
    RenderVec3 normal[6];  ///< world unit outward normal of face kind f = 2 axis + (side > 0)

    std::size_t cell(int i, int j, int k) const
    {
        return (static_cast<std::size_t>(i) * static_cast<std::size_t>(n[1]) +
                static_cast<std::size_t>(j)) *
                   static_cast<std::size_t>(n[2]) +
               static_cast<std::size_t>(k);
    }
    std::size_t cells() const { return cell(n[0], 0, 0); }
};

/// A surface face: the clear-air cell it opens onto and its kind (2 axis + (side > 0)).
struct GatherFace {
    std::array<int, 3> air{0, 0, 0};
    int kind = 0;
};

/// What a face sees, cosine-weighted means over its outward hemisphere; [0] above the
/// horizon, [1] below (1 and 0 where a face has no direction on that side).
struct GatheredView {
    double transmittance[2] = {1.0, 1.0};
    double emitted[2][GatherLattice::kUnits] = {{0.0, 0.0, 0.0, 0.0}, {0.0, 0.0, 0.0, 0.0}};
};

/// The view of every face over `directions` directions, swept on blocks of stride^3 cells.
/// `clearance` (swept cells) is how far out along each direction from the air cell's centre
/// the sweep is read, so that a face does not read its own cloud from the interpolation's
/// neighbouring cells.
std::vector<GatheredView> gatherSurfaceLight(const GatherLattice& lattice,
                                             const std::vector<GatherFace>& faces, int directions,
                                             double clearance, int stride,
                                             const std::function<bool()>& cancelled = {});

}  // namespace cg::algo
