// Reading fog volumes from OpenVDB files (formats/VdbFile.h): what is accepted as it is, what is
// converted, and what is refused with the file and the grid named, truncated files included.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include <openvdb/io/File.h>
#include <openvdb/tools/LevelSetSphere.h>

#include "formats/FormatError.h"
#include "formats/VdbFile.h"
#include "support/TestUtil.h"

namespace cg::formats {

namespace {

namespace fs = std::filesystem;

constexpr std::uint64_t kPlenty = std::uint64_t{1} << 30;

/// A small fog volume: a box of values 0.05..1.5 (above 1 too, as Houdini's can be), a tile,
/// and metadata of a plain kind and of a kind the cache does not store.
openvdb::FloatGrid::Ptr sampleFog(const std::string& name = "density")
{
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName(name);
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(2.5));
    auto acc = grid->getAccessor();
    for (int x = -6; x < 10; ++x)
        for (int y = 0; y < 7; ++y)
            for (int z = 3; z < 12; ++z)
                acc.setValue({x, y, z}, 0.05f + 0.01f * float((x + 7) * (y + 1) + z));
    grid->tree().addTile(1, openvdb::Coord(64, 64, 64), 0.25f, true);
    grid->insertMeta("units", openvdb::StringMetadata("metres"));
    grid->insertMeta("offset", openvdb::Vec3DMetadata(openvdb::Vec3d(1, 2, 3)));
    return grid;
}

fs::path writeGrids(const fs::path& path, const openvdb::GridCPtrVec& grids)
{
    openvdb::io::File file(path.string());
    file.write(grids);
    file.close();
    return path;
}

/// The message of the FormatError that reading `grid` of `path` throws, or fails the test.
std::string refusal(const fs::path& path, const std::string& grid = "density",
                    std::uint64_t maxBytes = kPlenty)
{
    try {
        readVdbFogVolume(path, grid, maxBytes);
    } catch (const FormatError& e) {
        EXPECT_EQ(e.where(), path.string());
        EXPECT_NE(e.message().find("grid '" + grid + "'"), std::string::npos) << e.what();
        return e.message();
    }
    ADD_FAILURE() << path << " grid " << grid << " was accepted";
    return "";
}

/// Values and active states of `a` and `b` differ at how many voxels (tiles expanded)?
std::size_t differences(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b)
{
    std::size_t n = 0;
    auto acc = b.getConstAccessor();
    for (auto it = a.cbeginValueOn(); it; ++it) {
        openvdb::CoordBBox box;
        it.getBoundingBox(box);
        for (auto c = box.begin(); c; ++c) n += !acc.isValueOn(*c) || acc.getValue(*c) != *it;
    }
    return n + (a.activeVoxelCount() != b.activeVoxelCount());
}

}  // namespace

TEST(VdbFile, AFogVolumeReadsBackVoxelForVoxelAsDensity)
{
    test::TempDir dir;
    const auto fog = sampleFog("smoke");
    const fs::path path = writeGrids(dir / "fog.vdb", {fog});
    const VdbGridSummary s = inspectVdbFogVolume(path, "smoke", kPlenty);
    EXPECT_EQ(s.valueType, "float");
    EXPECT_EQ(s.gridClass, "fog volume");
    EXPECT_EQ(s.activeVoxels, fog->activeVoxelCount());
    EXPECT_GT(s.memoryBytes, 0u);

    const auto read = readVdbFogVolume(path, "smoke", kPlenty);
    EXPECT_EQ(read->getName(), "density");
    EXPECT_EQ(read->getGridClass(), openvdb::GRID_FOG_VOLUME);
    EXPECT_FALSE(read->saveFloatAsHalf());
    EXPECT_EQ(read->transform(), fog->transform());
    EXPECT_EQ(differences(*fog, *read), 0u);
    EXPECT_EQ(differences(*read, *fog), 0u);
    EXPECT_EQ(read->metaValue<std::string>("units"), "metres");
    // Kinds the disk cache does not store, and the names OpenVDB owns, are dropped.
    EXPECT_FALSE(read->getMetadata<openvdb::Vec3DMetadata>("offset"));
    for (auto it = read->beginMeta(); it != read->endMeta(); ++it)
        EXPECT_NE(it->first.rfind("file_", 0), 0u) << it->first;
}

TEST(VdbFile, HalfFloatsReadBackAsTheHalfValuesAndDoublesAreConverted)
{
    test::TempDir dir;
    const auto fog = sampleFog();
    const auto half = fog->deepCopy();
    half->setSaveFloatAsHalf(true);
    writeGrids(dir / "half.vdb", {half});
    EXPECT_TRUE(inspectVdbFogVolume(dir / "half.vdb", "density", kPlenty).halfFloat);
    const auto read = readVdbFogVolume(dir / "half.vdb", "density", kPlenty);
    EXPECT_EQ(read->activeVoxelCount(), fog->activeVoxelCount());
    auto acc = read->getConstAccessor();
    std::size_t off = 0;
    for (auto it = fog->cbeginValueOn(); it.test(); ++it)
        if (it.isVoxelValue())
            off += acc.getValue(it.getCoord()) != float(openvdb::math::half(*it));
    EXPECT_EQ(off, 0u);

    auto doubles = openvdb::DoubleGrid::create(0.0);
    doubles->setName("density");
    doubles->setTransform(fog->transform().copy());
    doubles->tree().setValue({1, 2, 3}, 0.1);
    doubles->tree().setValue({-40, 2, 3}, 2.0);
    writeGrids(dir / "double.vdb", {doubles});
    const auto converted = readVdbFogVolume(dir / "double.vdb", "density", kPlenty);
    EXPECT_EQ(converted->activeVoxelCount(), 2u);
    EXPECT_EQ(converted->tree().getValue({1, 2, 3}), 0.1f);
    EXPECT_EQ(converted->tree().getValue({-40, 2, 3}), 2.0f);
}

TEST(VdbFile, NegativeValuesBecomeZeroAndNonFiniteValuesAreRefusedWithTheirVoxel)
{
    test::TempDir dir;
    auto fog = sampleFog();
    fog->tree().setValue({0, 0, 3}, -0.25f);
    fog->tree().setValueOff({1, 0, 3}, -1e-3f);  // inactive values are sampled too
    const auto read = readVdbFogVolume(writeGrids(dir / "neg.vdb", {fog}), "density", kPlenty);
    EXPECT_EQ(read->tree().getValue({0, 0, 3}), 0.0f);
    EXPECT_TRUE(read->tree().isValueOn({0, 0, 3}));
    EXPECT_EQ(read->tree().getValue({1, 0, 3}), 0.0f);
    EXPECT_EQ(read->tree().getValue({2, 0, 3}), fog->tree().getValue({2, 0, 3}));

    for (const float bad :
         {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        auto broken = sampleFog();
        broken->tree().setValue({5, 6, 7}, bad);
        const std::string message = refusal(writeGrids(dir / "bad.vdb", {broken}));
        EXPECT_NE(message.find("(5, 6, 7)"), std::string::npos) << message;
        EXPECT_NE(message.find("finite"), std::string::npos) << message;
    }
    auto badTile = sampleFog();
    badTile->tree().addTile(1, openvdb::Coord(-64, 0, 0), std::nanf(""), false);
    EXPECT_NE(refusal(writeGrids(dir / "tile.vdb", {badTile})).find("(-64, 0, 0)"),
              std::string::npos);
}

TEST(VdbFile, AMissingGridIsRefusedWithTheGridsTheFileHas)
{
    test::TempDir dir;
    auto vel = openvdb::Vec3SGrid::create();
    vel->setName("vel");
    const fs::path path = writeGrids(dir / "g.vdb", {sampleFog("smoke"), vel});
    const std::string message = refusal(path, "density");
    EXPECT_NE(message.find("no such grid"), std::string::npos) << message;
    EXPECT_NE(message.find("'smoke' (float)"), std::string::npos) << message;
    EXPECT_NE(message.find("'vel' (vec3s)"), std::string::npos) << message;
    EXPECT_NE(refusal(path, "vel").find("vec3s"), std::string::npos);

    const fs::path none = writeGrids(dir / "none.vdb", {});
    EXPECT_NE(refusal(none).find("the file has no grids"), std::string::npos);
    EXPECT_NE(refusal(dir / "missing.vdb").find("cannot open"), std::string::npos);
}

TEST(VdbFile, LevelSetsAndFrustumsAreRefused)
{
    test::TempDir dir;
    auto sphere = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(10.0f, {}, 1.0f);
    sphere->setName("density");
    const std::string message = refusal(writeGrids(dir / "ls.vdb", {sphere}));
    EXPECT_NE(message.find("level set"), std::string::npos) << message;
    // Saved without its class, its background (the narrow band's width) gives it away.
    sphere->setGridClass(openvdb::GRID_UNKNOWN);
    EXPECT_NE(refusal(writeGrids(dir / "ls2.vdb", {sphere})).find("background"), std::string::npos);

    auto frustum = sampleFog();
    frustum->setTransform(openvdb::math::Transform::createFrustumTransform(
        openvdb::BBoxd({0, 0, 0}, {10, 10, 10}), 0.5, 2.0, 1.0));
    EXPECT_NE(refusal(writeGrids(dir / "frustum.vdb", {frustum})).find("non-linear"),
              std::string::npos);
}

TEST(VdbFile, AnAbsurdSizeIsRefusedFromTheRecordedCountsBeforeTheVoxelsAreRead)
{
    test::TempDir dir;
    const fs::path path = writeGrids(dir / "fog.vdb", {sampleFog()});
    // Room for the file but not for the tree it records; refused by inspect, which reads no
    // voxels.
    try {
        inspectVdbFogVolume(path, "density", fs::file_size(path) + 16);
        ADD_FAILURE() << "accepted";
    } catch (const FormatError& e) {
        EXPECT_NE(e.message().find("of memory, more than"), std::string::npos) << e.what();
    }
    // A dense 4096^3 tile of fog: 256 GiB once its voxels are counted, from a file of a few hundred
    // bytes.
    auto tile = openvdb::FloatGrid::create(0.0f);
    tile->setName("density");
    tile->tree().addTile(3, openvdb::Coord(0), 0.5f, true);
    const fs::path huge = writeGrids(dir / "huge.vdb", {tile});
    EXPECT_LT(fs::file_size(huge), 4096u);
    EXPECT_NE(refusal(huge, "density", std::uint64_t{1} << 30).find("active voxels"),
              std::string::npos);
}

TEST(VdbFile, TruncatedDamagedAndForeignFilesAreRefusedWithoutACrash)
{
    test::TempDir dir;
    for (const bool half : {false, true}) {
        auto fog = sampleFog();
        fog->setSaveFloatAsHalf(half);
        const std::string bytes = test::readFile(writeGrids(dir / "good.vdb", {fog}));
        ASSERT_GT(bytes.size(), 1000u);
        // Every length up to the grid's metadata, then 60 cuts through the tree.
        std::vector<std::size_t> cuts;
        for (std::size_t n = 0; n < 400; n += 7) cuts.push_back(n);
        for (std::size_t k = 0; k < 60; ++k) cuts.push_back(400 + (bytes.size() - 401) * k / 59);
        for (std::size_t cut : cuts) {
            if (cut >= bytes.size()) continue;
            test::writeFile(dir / "cut.vdb", bytes.substr(0, cut));
            try {
                readVdbFogVolume(dir / "cut.vdb", "density", kPlenty);
                ADD_FAILURE() << "half " << half << ": cut at " << cut << " of " << bytes.size()
                              << " was accepted";
            } catch (const FormatError& e) {
                EXPECT_EQ(e.where(), (dir / "cut.vdb").string());
            }
        }
    }
    test::writeFile(dir / "empty.vdb", "");
    refusal(dir / "empty.vdb");
    test::writeFile(dir / "text.vdb", "not a VDB file at all, only some text\n");
    refusal(dir / "text.vdb");
    EXPECT_NE(refusal(dir.path()).find("directory"), std::string::npos);
}

}  // namespace cg::formats
