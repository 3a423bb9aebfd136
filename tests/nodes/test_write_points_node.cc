// WritePoints: VDB Points files that read back through OpenVDB with every particle, its
// position (within the codec's quantisation) and its attributes exact, and vdb_print reading
// what we wrote.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <openvdb/io/File.h>
#include <openvdb/points/PointConversion.h>
#include <openvdb/points/PointCount.h>
#include <openvdb/points/PointDataGrid.h>
#include <openvdb/tools/PointIndexGrid.h>
#include <tbb/parallel_for.h>

#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Registry.h"
#include "formats/PointsGrid.h"
#include "nodes/data/DataTypes.h"
#include "nodes/volume/VolumeNodes.h"
#include "support/FixtureNodes.h"
#include "support/TestUtil.h"

namespace cg {

namespace {

namespace fs = std::filesystem;
namespace pts = openvdb::points;

struct Particle {
    openvdb::Vec3f p;
    std::int32_t level;
};

/// Every point of `grid` by its source id, in world space.
std::map<std::int64_t, Particle> pointsBySource(const pts::PointDataGrid& grid)
{
    std::map<std::int64_t, Particle> out;
    const auto& xf = grid.transform();
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) {
        const pts::AttributeHandle<openvdb::Vec3f> p(leaf->constAttributeArray("P"));
        const pts::AttributeHandle<std::int32_t> level(leaf->constAttributeArray("level"));
        const pts::AttributeHandle<std::int64_t> source(leaf->constAttributeArray("source"));
        for (auto idx = leaf->beginIndexOn(); idx; ++idx) {
            const openvdb::Vec3d voxel = idx.getCoord().asVec3d() + openvdb::Vec3d(p.get(*idx));
            out[source.get(*idx)] = {openvdb::Vec3f(xf.indexToWorld(voxel)), level.get(*idx)};
        }
    }
    return out;
}

/// 2000 particles in a 60 m ball around (100, -50, 1500) m, each with a unique source id
/// (including the largest uint32) and a level 1..5.
struct Cloud {
    std::vector<float> xyz;
    std::vector<std::uint8_t> levels;
    std::vector<std::uint32_t> sources;
};
Cloud makeCloud()
{
    Cloud c;
    for (std::uint32_t i = 0; i < 2000; ++i) {
        const double t = 0.618034 * i, r = 60.0 * std::cbrt((i + 0.5) / 2000.0);
        const double z = 1.0 - 2.0 * (i + 0.5) / 2000.0, s = std::sqrt(1.0 - z * z);
        c.xyz.insert(c.xyz.end(), {static_cast<float>(100.0 + r * s * std::cos(6.2832 * t)),
                                   static_cast<float>(-50.0 + r * s * std::sin(6.2832 * t)),
                                   static_cast<float>(1500.0 + r * z)});
        c.levels.push_back(static_cast<std::uint8_t>(1 + i % 5));
        c.sources.push_back(i == 0 ? 0xFFFFFFFFu : i * 7919u);
    }
    return c;
}

void expectRoundTrip(const Cloud& c, const pts::PointDataGrid& grid, double tolerance)
{
    const auto read = pointsBySource(grid);
    ASSERT_EQ(read.size(), c.levels.size());
    EXPECT_EQ(pts::pointCount(grid.tree()), c.levels.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < c.levels.size(); ++i) {
        const auto it = read.find(static_cast<std::int64_t>(c.sources[i]));
        ASSERT_NE(it, read.end()) << "source " << c.sources[i];
        EXPECT_EQ(it->second.level, c.levels[i]);
        for (int a = 0; a < 3; ++a)
            worst = std::max(worst, std::fabs(double(it->second.p[a]) - c.xyz[3 * i + a]));
    }
    EXPECT_LE(worst, tolerance);
}

}  // namespace

TEST(PointsGrid, KeepsEveryParticleAndItsAttributes)
{
    const Cloud c = makeCloud();
    formats::PointsGridSettings s;
    s.voxelSize = 2.0;
    const auto fixed = formats::makeParticlePointsGrid(c.xyz.data(), c.levels.data(),
                                                       c.sources.data(), c.levels.size(), s);
    EXPECT_EQ(fixed->getName(), "points");
    EXPECT_EQ(fixed->voxelSize(), openvdb::Vec3d(2.0));
    // 16-bit offsets in a 2 m voxel: 2 m / 2^16 = 3e-5 m, plus float rounding at ~1.5 km.
    expectRoundTrip(c, *fixed, 2.0 / 65536.0 + 2e-4);

    s.precision = formats::PointPrecision::Float;
    s.voxelSize = 0.0;  // automatic
    const auto exact = formats::makeParticlePointsGrid(c.xyz.data(), c.levels.data(),
                                                       c.sources.data(), c.levels.size(), s);
    EXPECT_GT(exact->voxelSize()[0], 0.0);
    expectRoundTrip(c, *exact, 2e-4);
}

namespace {

/// What OpenVDB's own conversion makes of the particles: createPointIndexGrid,
/// createPointDataGrid and populateAttribute, the voxel size from computeVoxelSize when 0.
pts::PointDataGrid::Ptr openVdbConversion(const Cloud& c, const formats::PointsGridSettings& s)
{
    std::vector<openvdb::Vec3f> positions;
    for (std::size_t i = 0; i < c.levels.size(); ++i)
        positions.emplace_back(c.xyz[3 * i], c.xyz[3 * i + 1], c.xyz[3 * i + 2]);
    const std::vector<std::int32_t> levels(c.levels.begin(), c.levels.end());
    const std::vector<std::int64_t> sources(c.sources.begin(), c.sources.end());
    const pts::PointAttributeVector<openvdb::Vec3f> wrapper(positions);
    const double size =
        s.voxelSize > 0.0 ? s.voxelSize : pts::computeVoxelSize(wrapper, s.pointsPerVoxel);
    const auto xform = openvdb::math::Transform::createLinearTransform(size);
    const auto index =
        openvdb::tools::createPointIndexGrid<openvdb::tools::PointIndexGrid>(wrapper, *xform);
    auto grid =
        s.precision == formats::PointPrecision::Fixed16
            ? pts::createPointDataGrid<pts::FixedPointCodec<false>, pts::PointDataGrid>(
                  *index, wrapper, *xform)
            : pts::createPointDataGrid<pts::NullCodec, pts::PointDataGrid>(*index, wrapper, *xform);
    pts::appendAttribute<std::int32_t>(grid->tree(), "level");
    pts::populateAttribute(grid->tree(), index->tree(), "level",
                           pts::PointAttributeVector<std::int32_t>(levels));
    pts::appendAttribute<std::int64_t>(grid->tree(), "source");
    pts::populateAttribute(grid->tree(), index->tree(), "source",
                           pts::PointAttributeVector<std::int64_t>(sources));
    return grid;
}

/// Same voxel size, leaves, offsets, and per point the same position offset, level and source.
void expectSameGrid(const pts::PointDataGrid& a, const pts::PointDataGrid& b)
{
    ASSERT_EQ(a.voxelSize(), b.voxelSize());
    ASSERT_EQ(a.tree().leafCount(), b.tree().leafCount());
    auto lb = b.tree().cbeginLeaf();
    for (auto la = a.tree().cbeginLeaf(); la; ++la, ++lb) {
        ASSERT_EQ(la->origin(), lb->origin());
        ASSERT_EQ(la->getValueMask(), lb->getValueMask()) << la->origin();
        for (openvdb::Index n = 0; n < la->SIZE; ++n) ASSERT_EQ(la->getValue(n), lb->getValue(n));
        const pts::AttributeHandle<openvdb::Vec3f> pa(la->constAttributeArray("P")),
            pb(lb->constAttributeArray("P"));
        const pts::AttributeHandle<std::int32_t> va(la->constAttributeArray("level")),
            vb(lb->constAttributeArray("level"));
        const pts::AttributeHandle<std::int64_t> sa(la->constAttributeArray("source")),
            sb(lb->constAttributeArray("source"));
        for (openvdb::Index i = 0; i < la->pointCount(); ++i) {
            ASSERT_EQ(pa.get(i), pb.get(i)) << la->origin() << " point " << i;
            ASSERT_EQ(va.get(i), vb.get(i));
            ASSERT_EQ(sa.get(i), sb.get(i));
        }
    }
}

}  // namespace

// The grid built from chunks (handed over concurrently, in reverse order) is OpenVDB's own
// conversion of the same particles value for value, with its automatic voxel size too; the
// particles are clustered so that voxels hold many, whose order is the particles'.
TEST(PointsGrid, ChunkedBuildEqualsOpenVdbConversionValueForValue)
{
    Cloud c = makeCloud();
    for (std::size_t i = 0; i < c.levels.size(); ++i)  // two copies of each particle, far apart
        c.xyz.insert(c.xyz.end(), {c.xyz[3 * i] + 0.3f, c.xyz[3 * i + 1], c.xyz[3 * i + 2]});
    c.levels.insert(c.levels.end(), c.levels.begin(), c.levels.end());
    for (std::size_t i = 0, n = c.sources.size(); i < n; ++i)
        c.sources.push_back(c.sources[i] ^ 0x55u);
    constexpr std::size_t kChunk = 333;
    const std::size_t count = c.levels.size(), chunkCount = (count + kChunk - 1) / kChunk;
    const formats::ParticleChunks chunks = [&](const auto& consume, bool attributes) {
        tbb::parallel_for(std::size_t(0), chunkCount, [&](std::size_t k) {
            const std::size_t first = (chunkCount - 1 - k) * kChunk;
            consume({first, std::min(kChunk, count - first), c.xyz.data() + 3 * first,
                     attributes ? c.levels.data() + first : nullptr,
                     attributes ? c.sources.data() + first : nullptr});
        });
    };
    for (const double voxelSize : {0.0, 2.0, 25.0})
        for (const auto precision :
             {formats::PointPrecision::Fixed16, formats::PointPrecision::Float}) {
            SCOPED_TRACE(voxelSize);
            formats::PointsGridSettings s;
            s.voxelSize = voxelSize;
            s.precision = precision;
            const formats::ParticlePointsGridBuilder builder(chunks, s);
            EXPECT_EQ(builder.count(), count);
            const auto ours = builder.build();
            const auto reference = openVdbConversion(c, s);
            expectSameGrid(*ours, *reference);
            if (voxelSize == 25.0) {
                EXPECT_GT(ours->tree().cbeginLeaf()->pointCount(), 50u);
            }
        }
}

TEST(PointsGrid, EmptyAndNonFiniteInput)
{
    const auto empty = formats::makeParticlePointsGrid(nullptr, nullptr, nullptr, 0, {});
    EXPECT_EQ(pts::pointCount(empty->tree()), 0u);
    const float bad[3] = {0.0f, std::nanf(""), 0.0f};
    const std::uint8_t level = 1;
    const std::uint32_t source = 0;
    EXPECT_THROW(formats::makeParticlePointsGrid(bad, &level, &source, 1, {}),
                 std::invalid_argument);
}

namespace {

class WritePointsTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        registerCoreDataTypes(registry);
        registerNodeDataTypes(registry);
        registerFixtureNodes(registry);
        registerWritePointsNode(registry);
    }

    /// `cloudParams`: {"radius": 1, "spacing": 100} gives no particle at all (the lattice's
    /// only point, (-1, -1, -1), lies outside the ball).
    Graph parse(const std::string& writeParams,
                const std::string& cloudParams = R"({"radius": 12, "spacing": 2})")
    {
        return parseGraph(R"({"cloudgraph": 1, "nodes": {
            "cloud": {"type": "TestCloudSource", "params": )" +
                              cloudParams + R"(},
            "write": {"type": "WritePoints", "inputs": {"particles": "cloud.particles"},
                      "params": )" +
                              writeParams + "}}}",
                          "test.json", registry);
    }

    fs::path write(const Graph& g, int frame)
    {
        EvaluatorOptions options;
        options.outDir = out.path();
        Evaluator ev(registry, options);
        const auto files =
            std::dynamic_pointer_cast<const TextData>(ev.pull(g, "write", frame)->at("files"));
        return files ? fs::path(files->value) : fs::path();
    }

    Registry registry;
    test::TempDir out;
};

pts::PointDataGrid::Ptr readBack(const fs::path& path)
{
    openvdb::io::File file(path.string());
    file.open();
    const auto base = file.readGrid("points");
    file.close();
    return openvdb::gridPtrCast<pts::PointDataGrid>(base);
}

}  // namespace

TEST_F(WritePointsTest, WritesAFilePerFrameThatReadsBack)
{
    const fs::path path = write(parse(R"({"file": "pts/cloud.####.vdb", "voxelSize": 1.5})"), 42);
    EXPECT_EQ(path, out / "pts/cloud.0042.vdb");
    ASSERT_TRUE(fs::is_regular_file(path));
    std::size_t entries = 0;  // the temp file was renamed, not left beside it
    for (const auto& e : fs::directory_iterator(out / "pts")) entries += e.is_regular_file();
    EXPECT_EQ(entries, 1u);

    const auto grid = readBack(path);
    ASSERT_TRUE(grid);
    EXPECT_EQ(grid->voxelSize(), openvdb::Vec3d(1.5));
    EXPECT_EQ(grid->metaValue<openvdb::Int32>("frame"), 42);
    EXPECT_EQ(grid->metaValue<std::string>("units"), "metres");
    // TestCloudSource: a 2 m lattice in a 12 m ball, level 1, source 0.
    std::size_t count = 0, offLattice = 0;
    for (auto leaf = grid->tree().cbeginLeaf(); leaf; ++leaf) {
        const pts::AttributeHandle<openvdb::Vec3f> p(leaf->constAttributeArray("P"));
        const pts::AttributeHandle<std::int32_t> level(leaf->constAttributeArray("level"));
        const pts::AttributeHandle<std::int64_t> source(leaf->constAttributeArray("source"));
        for (auto idx = leaf->beginIndexOn(); idx; ++idx, ++count) {
            EXPECT_EQ(level.get(*idx), 1);
            EXPECT_EQ(source.get(*idx), 0);
            const auto w = grid->transform().indexToWorld(idx.getCoord().asVec3d() +
                                                          openvdb::Vec3d(p.get(*idx)));
            for (int a = 0; a < 3; ++a)
                offLattice += std::fabs(w[a] / 2.0 - std::round(w[a] / 2.0)) > 1e-4;
        }
    }
    EXPECT_GT(count, 500u);
    EXPECT_EQ(offLattice, 0u);
}

TEST_F(WritePointsTest, VdbPrintReadsTheWrittenFile)
{
    const std::string vdbPrint = test::findOnPath("vdb_print");
    ASSERT_FALSE(vdbPrint.empty())
        << "vdb_print is not on PATH: install the Debian package libopenvdb-tools "
           "(scripts/install-deps.sh lists it); this test needs it and does not skip";
    const fs::path path = write(parse(R"({"file": "print.####.vdb"})"), 5);
    const test::ProgramResult run =
        test::runProgram({vdbPrint, path.string(), "-l", "-m"}, out / "vdb_print.log");
    const std::string& output = run.output;
    ASSERT_EQ(run.status, 0) << output;
    EXPECT_NE(output.find("points"), std::string::npos) << output;
    EXPECT_NE(output.find("ptdataidx"), std::string::npos) << output;    // the point grid type
    EXPECT_NE(output.find("WritePoints"), std::string::npos) << output;  // our creator
}

TEST_F(WritePointsTest, EveryNthFrameOnly)
{
    const Graph g = parse(R"({"file": "e.####.vdb", "every": 3})");
    EXPECT_FALSE(write(g, 0).empty());
    EXPECT_TRUE(write(g, 1).empty());
    EXPECT_FALSE(fs::exists(out / "e.0001.vdb"));
}

TEST_F(WritePointsTest, FramesWithoutParticlesWriteNoFileUnlessAsked)
{
    const std::string empty = R"({"radius": 1, "spacing": 100})";
    EXPECT_TRUE(write(parse(R"({"file": "a.####.vdb"})", empty), 3).empty());
    EXPECT_FALSE(fs::exists(out / "a.0003.vdb"));

    const fs::path path = write(parse(R"({"file": "b.####.vdb", "skipEmpty": false})", empty), 3);
    EXPECT_EQ(path, out / "b.0003.vdb");
    const auto grid = readBack(path);
    ASSERT_TRUE(grid);
    EXPECT_EQ(pts::pointCount(grid->tree()), 0u);
}

TEST_F(WritePointsTest, FirstFrameAnchorsEvery)
{
    const Graph g = parse(R"({"file": "f.####.vdb", "every": 2, "firstFrame": 5})");
    EXPECT_TRUE(write(g, 4).empty());  // before firstFrame
    EXPECT_FALSE(write(g, 5).empty());
    EXPECT_TRUE(write(g, 6).empty());
    EXPECT_FALSE(write(g, 7).empty());
}

}  // namespace cg
