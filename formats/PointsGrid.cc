#include "formats/PointsGrid.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <openvdb/points/PointAttribute.h>
#include <openvdb/points/PointConversion.h>
#include <openvdb/tools/PointIndexGrid.h>

namespace cg::formats {

namespace {

template <class Codec>
openvdb::points::PointDataGrid::Ptr build(const openvdb::tools::PointIndexGrid& index,
                                          const openvdb::points::PointAttributeVector<openvdb::Vec3f>& p,
                                          const openvdb::math::Transform& transform)
{
    return openvdb::points::createPointDataGrid<Codec, openvdb::points::PointDataGrid>(
        index, p, transform);
}

}  // namespace

openvdb::points::PointDataGrid::Ptr makeParticlePointsGrid(const float* xyz,
                                                           const std::uint8_t* levels,
                                                           const std::uint32_t* sources,
                                                           std::size_t count,
                                                           const PointsGridSettings& settings)
{
    namespace pts = openvdb::points;
    if (!(settings.voxelSize >= 0.0) || !std::isfinite(settings.voxelSize))
        throw std::invalid_argument("points grid: voxel size must be >= 0 (0 = automatic)");
    if (settings.pointsPerVoxel < 1)
        throw std::invalid_argument("points grid: points per voxel must be >= 1");

    std::vector<openvdb::Vec3f> positions(count);
    std::vector<std::int32_t> level(count);
    std::vector<std::int64_t> source(count);
    for (std::size_t i = 0; i < count; ++i) {
        const float x = xyz[3 * i], y = xyz[3 * i + 1], z = xyz[3 * i + 2];
        if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
            throw std::invalid_argument("points grid: particle " + std::to_string(i) +
                                        " has a non-finite position");
        positions[i] = {x, y, z};
        level[i] = levels[i];
        source[i] = sources[i];
    }
    const pts::PointAttributeVector<openvdb::Vec3f> wrapper(positions);

    double voxelSize = settings.voxelSize;
    if (voxelSize == 0.0) {
        // computeVoxelSize needs points to measure; one voxel per metre is as good as any.
        voxelSize = count == 0 ? 1.0 : pts::computeVoxelSize(wrapper, settings.pointsPerVoxel);
    }
    const auto transform = openvdb::math::Transform::createLinearTransform(voxelSize);
    const auto index =
        openvdb::tools::createPointIndexGrid<openvdb::tools::PointIndexGrid>(wrapper, *transform);

    pts::PointDataGrid::Ptr grid =
        settings.precision == PointPrecision::Fixed16
            ? build<pts::FixedPointCodec</*OneByte=*/false>>(*index, wrapper, *transform)
            : build<pts::NullCodec>(*index, wrapper, *transform);

    pts::appendAttribute<std::int32_t>(grid->tree(), "level");
    pts::populateAttribute<pts::PointDataTree, openvdb::tools::PointIndexTree,
                           pts::PointAttributeVector<std::int32_t>>(
        grid->tree(), index->tree(), "level", pts::PointAttributeVector<std::int32_t>(level));
    pts::appendAttribute<std::int64_t>(grid->tree(), "source");
    pts::populateAttribute<pts::PointDataTree, openvdb::tools::PointIndexTree,
                           pts::PointAttributeVector<std::int64_t>>(
        grid->tree(), index->tree(), "source", pts::PointAttributeVector<std::int64_t>(source));

    grid->setName("points");
    return grid;
}

}  // namespace cg::formats
