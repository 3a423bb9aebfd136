#include "algo/volume/VelocityField.h"

#include <openvdb/tree/LeafManager.h>

namespace cg::algo {

namespace {

/// The fallback's cells, in fine cells: far enough to reach florets grown past the splats.
constexpr double kCoarseFactor = 4.0;

/// The interpolated velocity at world point x from `fine`, else `coarse`; zero where neither
/// has a particle's cell among the corners.
openvdb::Vec3f velocityAt(const CopyOriginField::Block& fine, const CopyOriginField::Block& coarse,
                          const openvdb::Vec3d& x)
{
    const double at[3] = {x[0], x[1], x[2]};
    double v[3];
    if (fine.origin(at, v) || coarse.origin(at, v))
        return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
    return openvdb::Vec3f(0.0f);
}

}  // namespace

VelocityFieldBuilder::VelocityFieldBuilder(double cellSize)
    : mFine(cellSize), mCoarse(kCoarseFactor * cellSize)
{
}

void VelocityFieldBuilder::add(const float* xyz, const float* velocities, std::size_t count)
{
    mFine.addVectors(xyz, velocities, count);
    mCoarse.addVectors(xyz, velocities, count);
}

openvdb::Vec3fGrid::Ptr VelocityFieldBuilder::build(const openvdb::FloatGrid& density,
                                                    const std::function<void()>& checkCancelled)
{
    mFine.finish();
    mCoarse.finish();
    auto vel = openvdb::Vec3fGrid::create(openvdb::Vec3f(0.0f));
    vel->setName("vel");
    vel->setVectorType(openvdb::VEC_CONTRAVARIANT_RELATIVE);
    vel->setTransform(density.transform().copy());
    vel->tree().topologyUnion(density.tree());
    vel->tree().voxelizeActiveTiles();
    const openvdb::math::Transform& xf = vel->transform();
    openvdb::tree::LeafManager<openvdb::Vec3fTree> leaves(vel->tree());
    leaves.foreach ([&](openvdb::Vec3fTree::LeafNodeType& leaf, std::size_t) {
        if (checkCancelled) checkCancelled();
        const openvdb::CoordBBox box = leaf.getNodeBoundingBox();
        const openvdb::Vec3d lo = xf.indexToWorld(box.min()), hi = xf.indexToWorld(box.max());
        const double l[3] = {lo[0], lo[1], lo[2]}, h[3] = {hi[0], hi[1], hi[2]};
        const CopyOriginField::Block fine = mFine.block(l, h);
        const CopyOriginField::Block coarse = mCoarse.block(l, h);
        for (auto it = leaf.beginValueOn(); it; ++it)
            it.setValue(velocityAt(fine, coarse, xf.indexToWorld(it.getCoord())));
    });
    return vel;
}

}  // namespace cg::algo
