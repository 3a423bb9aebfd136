#pragma once
// Small fog volumes with known optical depths, for the renderers' tests.

#include <cstddef>
#include <cstring>
#include <functional>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <openvdb/openvdb.h>

#include "algo/render/integrators/RenderVolume.h"

namespace cg::test {

/// An empty fog volume named "density" with cubic voxels of `voxel` metres.
inline openvdb::FloatGrid::Ptr makeFogGrid(double voxel)
{
    openvdb::initialize();
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel));
    return grid;
}

/// A box of voxels `lo`..`hi` (inclusive) of constant density, stored as active tiles and
/// voxels. Along an axis its trilinear density integrates to (hi − lo + 1) voxels: a plateau
/// between the outer voxel centres and a one-voxel ramp to zero outside each face.
inline openvdb::FloatGrid::Ptr makeBox(double voxel, const openvdb::Coord& lo,
                                       const openvdb::Coord& hi, float density)
{
    auto grid = makeFogGrid(voxel);
    grid->tree().fill(openvdb::CoordBBox(lo, hi), density, true);
    return grid;
}

/// The cube of voxels [0, n)^3.
inline openvdb::FloatGrid::Ptr makeBox(double voxel, int n, float density)
{
    return makeBox(voxel, openvdb::Coord(0), openvdb::Coord(n - 1), density);
}

/// A voxelised ball: every voxel whose centre is within r voxels of the origin.
inline openvdb::FloatGrid::Ptr makeBall(double voxel, int r, float density)
{
    auto grid = makeFogGrid(voxel);
    auto acc = grid->getAccessor();
    for (int i = -r; i <= r; ++i)
        for (int j = -r; j <= r; ++j)
            for (int k = -r; k <= r; ++k)
                if (i * i + j * j + k * k <= r * r) acc.setValue(openvdb::Coord(i, j, k), density);
    return grid;
}

/// Rec. 709 luminance of pixel (x, y) of an RGBA image.
inline double luminance(const std::vector<float>& rgba, int width, int x, int y)
{
    const float* p = &rgba[(static_cast<std::size_t>(y) * width + x) * 4];
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

/// Renders with `render` under 1 and then 2 threads and expects the same bytes in the beauty
/// and the background; returns the one-thread image.
inline algo::RenderedImage expectSameImageForAnyThreadCount(
    const std::function<algo::RenderedImage()>& render)
{
    algo::RenderedImage one, two;
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
        one = render();
    }
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
        two = render();
    }
    EXPECT_EQ(one.rgba.size(), two.rgba.size());
    EXPECT_EQ(one.background.size(), two.background.size());
    if (one.rgba.size() == two.rgba.size()) {
        EXPECT_EQ(std::memcmp(one.rgba.data(), two.rgba.data(), one.rgba.size() * sizeof(float)),
                  0);
    }
    if (one.background.size() == two.background.size()) {
        EXPECT_EQ(std::memcmp(one.background.data(), two.background.data(),
                              one.background.size() * sizeof(float)),
                  0);
    }
    return one;
}

}  // namespace cg::test
