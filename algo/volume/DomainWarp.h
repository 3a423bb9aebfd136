#pragma once
/// Fractal outlines that ride with the cloud: the splatted density is resampled at points
/// displaced by a vector fractal noise, v'(x) = v(x + w(x)), the "domain warping" of
/// procedural texturing (Ebert et al., "Texturing and Modeling", 2003). Splats leave an
/// envelope that is smooth at every scale below the particle; a warp whose octaves reach
/// from the turrets' size down to a few voxels bends it into lobes, necks and overhangs at
/// every scale in between, as real cumulus outlines are (perimeter dimension about 1.35,
/// Lovejoy 1982). The octaves' amplitudes fall by `roughness` each time the wavelength
/// halves: a fractal boundary of dimension about 2 - log2(1 / roughness) over the octaves.
///
/// w rides with the copies: each cell of the copies' territory (algo/volume/CopyTerritory.h)
/// evaluates it at the point's place in its owner's coordinates (the point minus the copy's
/// origin, R P_f of Eq. 10 plus its drift), and a point blends the warps of the eight cells
/// around it trilinearly. Inside one copy's territory the lobes move rigidly with it; where
/// territories meet, the warps cross-fade over one cell. The warp is never evaluated in a
/// blend of copies' coordinates, which is nearly constant where many copies overlap (as
/// everywhere in a tower) and would only shift the envelope. Where no copy reaches, world
/// coordinates.
///
/// Deterministic for any thread count: each output voxel reads only the input grid, its
/// position and the origin field. No engine includes.

#include <functional>

#include <openvdb/openvdb.h>

#include "algo/volume/CopyTerritory.h"

namespace cg::algo {

struct DomainWarpSettings {
    /// Largest displacement of the first octave, metres (0: the grid is left untouched).
    double amplitude = 0.0;
    /// Wavelength of the first octave, metres (> 0).
    double wavelength = 1000.0;
    /// Octaves, each half the wavelength of the one before.
    int octaves = 4;
    /// Amplitude ratio between successive octaves, in (0, 1].
    double roughness = 0.6;
};

/// Throws std::invalid_argument naming the setting that is out of range.
void checkDomainWarpSettings(const DomainWarpSettings& settings);

/// How far any voxel can be displaced (metres): the bound of the octaves' sum.
double domainWarpReach(const DomainWarpSettings& settings);

/// The vector warp at a point already in its copy's coordinates (metres).
void domainWarpAt(const double x[3], const DomainWarpSettings& settings, double w[3]);

/// Resamples `grid` (a fog volume) in place, trilinearly, at every voxel's displaced point;
/// the active voxels grow by the warp's reach where the cloud is pushed out and voxels that
/// sample nothing are switched off. `territory` null: world coordinates. `checkCancelled`
/// (optional) is called between phases and may throw.
void warpVolume(openvdb::FloatGrid& grid, const CopyTerritory* territory,
                const DomainWarpSettings& settings,
                const std::function<void()>& checkCancelled = {});

}  // namespace cg::algo
