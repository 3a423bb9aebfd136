#include "algo/render/RenderRays.h"

#include <stdexcept>

namespace cg::algo {

namespace {

constexpr double kPi = 3.14159265358979323846;

void require(bool ok, const char* what)
{
    if (!ok) throw std::invalid_argument(what);
}

}  // namespace

CameraRays::CameraRays(const RenderCamera& camera)
{
    require(camera.width >= 1 && camera.height >= 1, "image size must be at least 1 x 1");
    require(camera.fovDegrees > 0.0 && camera.fovDegrees < 180.0,
            "field of view must be in (0, 180) degrees");
    const RenderVec3 view = camera.lookAt - camera.position;
    require(view.length() > 0.0, "camera look-at equals its position");
    mForward = view.unitSafe();
    mRight = mForward.cross(camera.up);
    require(mRight.length() > 1e-9 * camera.up.length() && camera.up.length() > 0.0,
            "camera up is zero or parallel to the view direction");
    mRight = mRight.unitSafe();
    mUp = mRight.cross(mForward);
    mTanHalf = std::tan(0.5 * camera.fovDegrees * kPi / 180.0);
    mWidth = camera.width;
    mHeight = camera.height;
    mAspect = double(camera.width) / double(camera.height);
}

RenderVec3 CameraRays::direction(int px, int py) const
{
    const double sx = (2.0 * (px + 0.5) / mWidth - 1.0) * mTanHalf * mAspect;
    const double sy = (1.0 - 2.0 * (py + 0.5) / mHeight) * mTanHalf;
    return (mForward + mRight * sx + mUp * sy).unitSafe();
}

IndexRay toIndexRay(const openvdb::math::Transform& xform, const RenderVec3& origin,
                    const RenderVec3& direction)
{
    const RenderVec3 o = xform.worldToIndex(origin);
    return {o, xform.worldToIndex(origin + direction) - o};
}

double renderVoxelSize(const openvdb::FloatGrid& grid)
{
    require(grid.transform().isLinear(), "fog volume: the renderer needs a linear transform");
    const openvdb::Vec3d v = grid.voxelSize();
    return std::min({v.x(), v.y(), v.z()});
}

}  // namespace cg::algo
