// The velocity grid beside a fog volume: exact for copies that move as a whole, linear
// fields reproduced, the density's topology kept, the same bits for any thread count.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "algo/volume/VelocityField.h"

namespace cg::algo {

namespace {

constexpr double kVoxel = 20.0;

/// A density grid of 20 m voxels, active in the boxes given (index space).
openvdb::FloatGrid::Ptr densityIn(std::initializer_list<openvdb::CoordBBox> boxes)
{
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(kVoxel));
    for (const auto& box : boxes)
        for (auto ijk = box.begin(); ijk; ++ijk) grid->tree().setValue(*ijk, 1.0f);
    return grid;
}

/// Particles on a 10 m lattice filling [lo, hi) metres, each with velocity v(x).
struct Lattice {
    std::vector<float> xyz, v;
    template <class F>
    Lattice(const openvdb::Vec3d& lo, const openvdb::Vec3d& hi, F velocity)
    {
        for (double x = lo[0] + 5; x < hi[0]; x += 10)
            for (double y = lo[1] + 5; y < hi[1]; y += 10)
                for (double z = lo[2] + 5; z < hi[2]; z += 10) {
                    const openvdb::Vec3d u = velocity(openvdb::Vec3d(x, y, z));
                    for (int k = 0; k < 3; ++k) {
                        xyz.push_back(static_cast<float>(k == 0 ? x : k == 1 ? y : z));
                        v.push_back(static_cast<float>(u[k]));
                    }
                }
    }
    std::size_t size() const { return xyz.size() / 3; }
};

}  // namespace

TEST(VelocityField, TwoCopiesMovingApartEachGiveTheirVoxelsTheirVelocity)
{
    // Two 400 m clumps 2 km apart, moving differently, voxels where they are.
    const openvdb::Vec3f va(3.0f, -1.5f, 8.0f), vb(-6.0f, 0.25f, 0.0f);
    const Lattice a({0, 0, 1000}, {400, 400, 1400}, [&](auto) { return openvdb::Vec3d(va); });
    const Lattice b({2000, 0, 1000}, {2400, 400, 1400}, [&](auto) { return openvdb::Vec3d(vb); });
    const auto density = densityIn({{{2, 2, 52}, {17, 17, 67}}, {{102, 2, 52}, {117, 17, 67}}});
    VelocityFieldBuilder builder(320.0);
    builder.add(a.xyz.data(), a.v.data(), a.size());
    builder.add(b.xyz.data(), b.v.data(), b.size());
    const auto vel = builder.build(*density);
    EXPECT_EQ(vel->getName(), "vel");
    EXPECT_EQ(vel->getVectorType(), openvdb::VEC_CONTRAVARIANT_RELATIVE);
    EXPECT_TRUE(vel->tree().hasSameTopology(density->tree()));
    EXPECT_EQ(vel->transform(), density->transform());
    std::size_t n = 0;
    for (auto it = vel->cbeginValueOn(); it; ++it, ++n) {
        const openvdb::Vec3f expected = it.getCoord().x() < 60 ? va : vb;
        EXPECT_LT((*it - expected).length(), 1e-4f) << it.getCoord();
    }
    EXPECT_EQ(n, 2u * 16 * 16 * 16);
}

TEST(VelocityField, AShearIsInterpolatedBetweenCellsAndFarVoxelsFallBackOrStill)
{
    // v_x = 0.01 z (wind shear), particles filling 0..1280 m in x, y and 0..1280 m in z.
    const Lattice shear({0, 0, 0}, {1280, 1280, 1280},
                        [](const openvdb::Vec3d& x) { return openvdb::Vec3d(0.01 * x[2], 0, 0); });
    // Voxels inside; one 120 m above the top (within a coarse cell's reach); one 6 km away.
    const auto density = densityIn({{{16, 16, 16}, {47, 47, 47}},
                                    {{32, 32, 70}, {32, 32, 70}},
                                    {{32, 32, 400}, {32, 32, 400}}});
    VelocityFieldBuilder builder(160.0);
    builder.add(shear.xyz.data(), shear.v.data(), shear.size());
    const auto vel = builder.build(*density);
    const auto acc = vel->getConstAccessor();
    for (int k = 16; k <= 47; ++k) {
        const double z = k * kVoxel;
        const openvdb::Vec3f v = acc.getValue({30, 20, k});
        EXPECT_NEAR(v[0], 0.01 * z, 1e-4) << "z " << z;  // cell means of a linear field
        EXPECT_EQ(v[1], 0.0f);
    }
    const openvdb::Vec3f above = acc.getValue({32, 32, 70});
    EXPECT_GT(above[0], 5.0f);  // the coarse cells' shear, not zero
    EXPECT_EQ(acc.getValue({32, 32, 400}), openvdb::Vec3f(0.0f));
}

TEST(VelocityField, TheGridIsTheSameForAnyThreadCountAndChunkOrder)
{
    const Lattice swirl({0, 0, 0}, {800, 800, 600}, [](const openvdb::Vec3d& x) {
        return openvdb::Vec3d(-(x[1] - 400) * 0.02, (x[0] - 400) * 0.02, 3.0 + 0.001 * x[2]);
    });
    const auto density = densityIn({{{0, 0, 0}, {39, 39, 29}}});
    const auto make = [&](int threads, bool reversed) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        VelocityFieldBuilder builder(200.0);
        const std::size_t chunk = 997, chunks = (swirl.size() + chunk - 1) / chunk;
        tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
            const std::size_t k = reversed ? chunks - 1 - c : c;
            const std::size_t first = k * chunk, count = std::min(chunk, swirl.size() - first);
            builder.add(&swirl.xyz[3 * first], &swirl.v[3 * first], count);
        });
        return builder.build(*density);
    };
    const auto one = make(1, false), two = make(2, true);
    auto b = two->getConstAccessor();
    std::size_t n = 0;
    for (auto it = one->cbeginValueOn(); it; ++it, ++n)
        ASSERT_EQ(std::memcmp(&*it, &b.getValue(it.getCoord()), sizeof(openvdb::Vec3f)), 0)
            << it.getCoord();
    EXPECT_EQ(n, two->activeVoxelCount());
}

TEST(VelocityField, AVelocityThatIsNotFiniteIsRefused)
{
    const float xyz[3] = {0, 0, 0}, v[3] = {0, NAN, 0};
    VelocityFieldBuilder builder(100.0);
    EXPECT_THROW(builder.add(xyz, v, 1), std::invalid_argument);
}

}  // namespace cg::algo
