#pragma once
/// The velocity a fog volume moves with, for motion blur: a vector grid beside the density,
/// active exactly where it is, each voxel the velocity of the cloud particles around it.
///
/// The particles' velocities (the mapper's Eq. 10 differentiated) are averaged per cubic
/// cell and interpolated between cell centres (CopyOriginField's integer sums, so the grid
/// does not depend on the thread count or the particles' order). Inside one copy that moves
/// as a whole every voxel gets the copy's velocity, which is also the velocity of the detail
/// the Voxelizer carves in the copy's coordinates. A voxel with no particle's cell among its
/// eight corners (detail grown beyond the particles) takes the average over cells four times
/// as large; none there either: zero. No engine includes.

#include <cstddef>
#include <functional>

#include <openvdb/openvdb.h>

#include "algo/volume/CopyOriginField.h"

namespace cg::algo {

class VelocityFieldBuilder {
public:
    /// cellSize in metres, > 0: about the splat radius or more, so that every voxel a
    /// particle reaches has it among its corners.
    explicit VelocityFieldBuilder(double cellSize);

    /// Adds `count` particles at `xyz` (metres) with `velocities` (m/s), 3 floats each. Safe
    /// to call from several threads at once. Throws std::invalid_argument for a velocity that
    /// is not finite.
    void add(const float* xyz, const float* velocities, std::size_t count);

    /// The grid "vel" (Vec3f, m/s, contravariant relative, as Houdini and Blender expect) on
    /// density's transform, active where density is. Call once, after every add.
    openvdb::Vec3fGrid::Ptr build(const openvdb::FloatGrid& density,
                                  const std::function<void()>& checkCancelled = {});

private:
    CopyOriginField mFine;
    CopyOriginField mCoarse;  ///< cells 4 times as large: the fallback
};

}  // namespace cg::algo
