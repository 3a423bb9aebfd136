#pragma once
/// Ray geometry shared by the fast renderer and the path tracer: the camera's pixel rays,
/// world rays mapped into the fog volume's index space, the ground plane and the sky dome.

#include <algorithm>
#include <cmath>
#include <limits>

#include <openvdb/openvdb.h>

#include "algo/render/RenderSettings.h"

namespace cg::algo {

/// The rays of a pinhole camera. Throws std::invalid_argument for an unusable camera (size
/// < 1, field of view outside (0, 180), looking at itself or along `up`).
class CameraRays {
public:
    explicit CameraRays(const RenderCamera& camera);

    /// Unit world direction of the ray through the centre of pixel (px, py), (0, 0) top left.
    RenderVec3 direction(int px, int py) const;

private:
    RenderVec3 mForward, mRight, mUp;
    double mTanHalf = 0.0;
    double mAspect = 1.0;
    int mWidth = 1, mHeight = 1;
};

/// A world ray mapped to index space: the index point at world distance t is o + t d.
struct IndexRay {
    RenderVec3 o;
    RenderVec3 d;
};

IndexRay toIndexRay(const openvdb::math::Transform& xform, const RenderVec3& origin,
                    const RenderVec3& direction);

/// Narrows [t0, t1] to where the ray origin + t dir lies in the box [lo, hi) (slab by slab);
/// false where it misses it (t0 > t1 then). Along an axis the ray does not move, it is in the
/// box where its origin is.
inline bool clipToBox(const RenderVec3& origin, const RenderVec3& dir, const double (&lo)[3],
                      const double (&hi)[3], double& t0, double& t1)
{
    for (int a = 0; a < 3; ++a) {
        if (dir[a] == 0.0) {
            if (origin[a] < lo[a] || origin[a] >= hi[a]) return false;
            continue;
        }
        double ta = (lo[a] - origin[a]) / dir[a];
        double tb = (hi[a] - origin[a]) / dir[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    return t0 <= t1;
}

/// The smallest voxel edge of `grid`, m. Throws std::invalid_argument for a non-linear
/// transform, which neither renderer can march.
double renderVoxelSize(const openvdb::FloatGrid& grid);

/// Distance along the ray to the ground plane z = 0 when the ground is drawn and the ray
/// goes down to it from above, +infinity otherwise.
inline double groundDistance(const RenderGround& ground, const RenderVec3& origin,
                             const RenderVec3& direction)
{
    if (ground.enabled && origin.z() > 0.0 && direction.z() < 0.0)
        return -origin.z() / direction.z();
    return std::numeric_limits<double>::infinity();
}

/// Radiance of the sky seen in unit direction `dir`: horizon + (zenith − horizon) sqrt(dir.z)
/// for dir.z > 0, the horizon colour below.
inline RenderVec3 skyRadiance(const RenderSky& sky, const RenderVec3& dir)
{
    if (!(dir.z() > 0.0)) return sky.horizon;
    const double w = std::sqrt(std::min(dir.z(), 1.0));
    return sky.horizon + (sky.zenith - sky.horizon) * w;
}

/// The camera's view of a ground point at distance `distance`: its radiance faded toward the
/// horizon colour as exp(−distance / hazeDistance) (no haze when hazeDistance is 0).
inline RenderVec3 hazedGround(const RenderSettings& s, const RenderVec3& radiance, double distance)
{
    if (!(s.ground.hazeDistance > 0.0)) return radiance;
    const double f = std::exp(-distance / s.ground.hazeDistance);
    return radiance * f + s.sky.horizon * (1.0 - f);
}

}  // namespace cg::algo
