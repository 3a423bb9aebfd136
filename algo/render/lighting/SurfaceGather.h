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
/// along −v, E = ∫ σ_t J exp(−τ) ds with J the cell's source radiance toward −v (its
/// scattered light, a lobe about its net flux as the renderer takes it, and the sun light it
/// scatters out of the beam). Each slice is blurred along the horizontal before the next
/// reads it, so a direction's sweep widens with distance as the cone of directions it
/// stands for does. Directions are points of a Fibonacci sphere (about equal solid angles);
/// a face takes the cosine-weighted means of T and E over the directions in its outward
/// hemisphere, above and below the horizon apart. The directions are swept one after
/// another and each slice's cells in parallel, so the result does not depend on the thread
/// count.
///
/// Where there is a ground (the plane z = 0), it is lit by more than the open sky and the
/// sun: a map of ground points gathers what each sees above it, the sky through the clouds
/// and their glow, over the directions above the horizon; then a face looking down reads,
/// per direction, the ground point its ray reaches, dimmed by the clouds on the way. So the
/// ground under a cloud is shaded from the sky and lit by the cloud, and a cloud's base
/// sees the sun-lit ground where it lies, not a mean of it.

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include <openvdb/openvdb.h>

#include "algo/render/RenderSettings.h"
#include "algo/render/lighting/GroundGrid.h"
#include "algo/render/media/Phase.h"

namespace cg::algo {

/// A dense box of cells, index (i n1 + j) n2 + k.
struct CellBox {
    int n[3] = {0, 0, 0};

    std::size_t cell(int i, int j, int k) const
    {
        return (static_cast<std::size_t>(i) * static_cast<std::size_t>(n[1]) +
                static_cast<std::size_t>(j)) *
                   static_cast<std::size_t>(n[2]) +
               static_cast<std::size_t>(k);
    }
    std::size_t cells() const { return cell(n[0], 0, 0); }
};

/// The lattice a gather runs on: a box of cells and its cells of cloud.
struct GatherLattice : CellBox {
    static constexpr int kUnits = 4;  ///< the lights whose scattered light is gathered
    /// A cell of cloud and the light it scatters. Per unit light, the fluence φ and net flux F
    /// of the light in it: it scatters albedo × diffuseScattered(φ, F) toward each direction
    /// (DiffuseLight.h), as the renderer has it. Per unit sun irradiance, `beam`: the light it
    /// scatters out of the sun's beam for the first time, per unit extinction, which goes out
    /// in the phase function's remainder lobe HG(g') about the sun's travel.
    struct Cloud {
        std::size_t cell = 0;
        float extinction = 0.0f;  ///< σ_t, 1/m
        float beam = 0.0f;
        float phi[kUnits] = {0.0f, 0.0f, 0.0f, 0.0f};
        float flux[kUnits][3] = {};  ///< world x, y, z
    };

    std::vector<Cloud> clouds;
    double albedo = 1.0;                ///< single-scattering albedo
    DeltaEddington split;               ///< of the phase function
    RenderVec3 travel{0.0, 0.0, -1.0};  ///< the sun's direction of travel
    /// World direction (per metre) to cells: a displacement d (m) moves cellsPerMetre * d.
    openvdb::Mat3d cellsPerMetre = openvdb::Mat3d::identity();
    RenderVec3 origin{0.0};  ///< world position (m) of the centre of cell (0, 0, 0)
    RenderVec3 normal[6];    ///< world unit outward normal of face kind f = 2 axis + (side > 0)
};

/// A surface face: the clear-air cell it opens onto and its kind (2 axis + (side > 0)).
struct GatherFace {
    std::array<int, 3> air{0, 0, 0};
    int kind = 0;
};

/// The ground plane z = 0, if there is one, and the map of its points that gather their
/// view of the sky. Beyond the map the ground sees the open sky.
struct GatherGround {
    bool present = false;
    GroundGrid map;
    /// The sun's transmittance down to a ground point; none where the sun does not light
    /// the ground (then SunLit is 0).
    std::function<double(const RenderVec3&)> sunlit;
    /// m: the radius of the box blur (two passes each way) the map gets once complete. With
    /// few directions a ground point sees a cloud along some and the sky along the rest, so
    /// the map holds a displaced copy of the cloud per direction (ray effects); a blur about
    /// as wide as the clouds are high, the scale on which a hemisphere's view changes, merges
    /// them. 0: none.
    double smoothing = 0.0;
};

/// What a ground point sees above it, cosine-weighted over the upper hemisphere: the sky's
/// transmittance and the clouds' glow per unit light.
struct GroundView {
    double sky = 1.0;
    double emitted[GatherLattice::kUnits] = {0.0, 0.0, 0.0, 0.0};
};

/// What a face sees, cosine-weighted means over its outward hemisphere; [0] above the
/// horizon, [1] below (1 and 0 where a face has no direction on that side).
struct GatheredView {
    /// The ground's light per its units: sky light (1 from open ground), sun light (the sun's
    /// transmittance to the ground), and the clouds' glow it sends back, per unit light.
    enum GroundUnit { SkyLit, SunLit, Glow, kGroundUnits = Glow + GatherLattice::kUnits };
    double transmittance[2] = {1.0, 1.0};
    double emitted[2][GatherLattice::kUnits] = {{0.0, 0.0, 0.0, 0.0}, {0.0, 0.0, 0.0, 0.0}};
    /// With a ground: below the horizon, the mean of T times what the ground point the
    /// direction reaches sends back, per ground unit (all 0 where a face does not look down).
    double ground[kGroundUnits] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
};

struct Gathered {
    std::vector<GatheredView> faces;
    std::vector<GroundView> ground;  ///< per point of the ground's map (row by row, x first)
};

/// The view of every face and ground point over `directions` directions, swept on blocks of
/// stride^3 cells. `clearance` (swept cells) is how far out along each direction from the
/// air cell's centre the sweep is read, so that a face does not read its own cloud from the
/// interpolation's neighbouring cells.
Gathered gatherSurfaceLight(const GatherLattice& lattice, const std::vector<GatherFace>& faces,
                            const GatherGround& ground, int directions, double clearance,
                            int stride, const std::function<bool()>& cancelled = {});

}  // namespace cg::algo
