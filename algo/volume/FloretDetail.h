#pragma once
/// Cauliflower turrets grown on a splatted cloud. The envelope the particles make (the
/// iso-surface v = 0.5 of the summed density v) becomes a signed distance field s (metres,
/// negative inside). The envelope sinks by the size of lumps its part of the cloud takes
/// (r0, or less where the part is too thin to hold a root of r0: algo/volume/NearbyDepth.h),
/// and florets (algo/volume/Florets.h) whose roots lie between 0.9 and 1.9 of their radius
/// inside it grow back out, so the cloud keeps its shape at the scale of the splats and
/// gains round lumps with smaller lumps on them, down to the smallest generation. Faces
/// that look down do not sink (a cumulus base is flat and smooth), and no lump grows down.
///
/// Each voxel keeps the coverage of f = max(-s - sink, florets' depth), a smoothstep over
/// one voxel, so the surface is crisp at any voxel size. A voxel's value is max(v, 0.5) times
/// its coverage: a lump that stands out of the envelope holds the surface's value. The grid
/// is dilated by how far lumps can stand out first, and whatever stays empty is switched
/// off again.
///
/// The florets ride with the copies: each root sits on the lattice of one copy's own
/// coordinates (the point minus the copy's origin, Eq. 12 plus its drift) and is kept only
/// inside that copy's territory (algo/volume/CopyTerritory.h), so it moves rigidly with the
/// copy, and no lump is evaluated in a blend of copies' coordinates (which, where copies
/// overlap as they do everywhere in a tower, squashes lumps into flat sheets). Without a
/// territory (particles that belong to no copy) the roots are fixed in world space.
/// Production tools grow cloud detail on a distance field the same way (Houdini's cloud
/// noise); the florets and their numbers are ours.
/// Deterministic for any thread count. No engine includes.

#include <functional>

#include <openvdb/openvdb.h>

#include "algo/volume/CopyTerritory.h"
#include "algo/volume/Florets.h"

namespace cg::algo {

/// Grows `grid` (a fog volume, values in [0, 1]) into florets in place; florets.radius 0
/// leaves it untouched. `territory` (null: world space) says which copy owns each region. A grid
/// whose values never cross 0.5 has no surface and is left as it is. Throws std::invalid_argument
/// for bad settings.
void growFlorets(openvdb::FloatGrid& grid, const FloretSettings& florets,
                 const CopyTerritory* territory, const std::function<void()>& checkCancelled = {});

}  // namespace cg::algo
