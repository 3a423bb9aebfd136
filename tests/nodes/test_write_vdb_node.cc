// WriteVDB: per-frame files that read back through OpenVDB with identical values, half floats,
// compression, atomic writing, the vdb_print program reading what we wrote, and which frames
// are written (firstFrame, every, skipEmpty) whatever frames a run cooks.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <openvdb/io/File.h>

#include "core/CoreData.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Node.h"
#include "core/Registry.h"
#include "nodes/DeclHelpers.h"
#include "nodes/data/DataTypes.h"
#include "nodes/data/FogVolume.h"
#include "nodes/volume/VolumeNodes.h"
#include "support/FixtureNodes.h"
#include "support/TestUtil.h"

namespace cg {

namespace {

namespace fs = std::filesystem;

/// A fog ball that exists from frame `appears` on; before it the grid has no active voxel,
/// as the Voxelizer's is before the cloud forms.
class GrowingFogNode final : public Node {
public:
    void cook(CookContext& ctx) override
    {
        auto grid = openvdb::FloatGrid::create(0.0f);
        grid->setName("density");
        grid->setGridClass(openvdb::GRID_FOG_VOLUME);
        if (ctx.frame() >= ctx.params().getInt("appears"))
            grid->fill(openvdb::CoordBBox({-2, -2, 0}, {2, 2, ctx.frame()}), 0.5f);
        ctx.setOutput("volume", std::make_shared<FogVolumeData>(grid));
    }
};

void registerGrowingFog(Registry& registry)
{
    NodeDecl d;
    d.type = "TestGrowingFog";
    d.category = "test";
    d.doc = "an empty fog volume before frame 'appears', a box growing with the frame after";
    d.frameDependent = true;
    d.outputs = {port("volume", "FogVolume", "the volume")};
    d.params = {intParam("appears", 3, "frame", "first frame with voxels", 0)};
    d.create = [] { return std::make_unique<GrowingFogNode>(); };
    registry.addNode(std::move(d));
}

class WriteVdbTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        registerCoreDataTypes(registry);
        registerNodeDataTypes(registry);
        registerFixtureNodes(registry);
        registerVoxelizerNode(registry);
        registerWriteVdbNode(registry);
        registerGrowingFog(registry);
    }

    /// A growing fog (voxels from frame 3) written by WriteVDB, frames 0..20.
    Graph parseGrowing(const std::string& writeParams)
    {
        return parseGraph(R"({"cloudgraph": 1, "frames": {"start": 0, "end": 20}, "nodes": {
            "fog": {"type": "TestGrowingFog", "params": {"appears": 3}},
            "write": {"type": "WriteVDB", "inputs": {"volume": "fog.volume"},
                      "params": )" +
                              writeParams + "}}}",
                          "growing.json", registry);
    }

    /// The frames of 0..20 written, each cooked by a fresh evaluator (nothing cooked before).
    std::vector<int> writtenFrames(const Graph& g)
    {
        std::vector<int> frames;
        for (int f = 0; f <= 20; ++f)
            if (!write(g, f).empty()) frames.push_back(f);
        return frames;
    }

    Graph parse(const std::string& writeParams)
    {
        return parseGraph(R"({"cloudgraph": 1, "nodes": {
            "cloud": {"type": "TestCloudSource", "params": {"radius": 25, "spacing": 2}},
            "vox": {"type": "Voxelizer", "inputs": {"particles": "cloud.particles"},
                    "params": {"voxelSize": 1.0, "radius": 3.0, "density": 0.3}},
            "write": {"type": "WriteVDB", "inputs": {"volume": "vox.volume"},
                      "params": )" +
                              writeParams + "}}}",
                          "test.json", registry);
    }

    /// Writes frame `frame` under out/ and returns the voxelizer's grid and the written path.
    fs::path write(const Graph& g, int frame, openvdb::FloatGrid::ConstPtr* grid = nullptr)
    {
        EvaluatorOptions options;
        options.outDir = out.path();
        Evaluator ev(registry, options);
        const auto files =
            std::dynamic_pointer_cast<const TextData>(ev.pull(g, "write", frame)->at("files"));
        if (grid) {
            const auto volume = ev.pull(g, "vox", frame)->at("volume");
            *grid = std::dynamic_pointer_cast<const FogVolumeData>(volume)->grid;
        }
        return files ? fs::path(files->value) : fs::path();
    }

    Registry registry;
    test::TempDir out;
};

openvdb::FloatGrid::Ptr readBack(const fs::path& path)
{
    openvdb::io::File file(path.string());
    file.open();
    const auto base = file.readGrid("density");
    file.close();
    return openvdb::gridPtrCast<openvdb::FloatGrid>(base);
}

}  // namespace

TEST_F(WriteVdbTest, WritesAFilePerFrameThatReadsBackIdentically)
{
    const Graph g = parse(R"({"file": "vdb/cloud.####.vdb"})");
    openvdb::FloatGrid::ConstPtr grid;
    const fs::path path = write(g, 42, &grid);
    EXPECT_EQ(path, out / "vdb/cloud.0042.vdb");
    ASSERT_TRUE(fs::is_regular_file(path));
    // Only the file itself: the temp file was renamed, not left beside it.
    std::size_t entries = 0;
    for (const auto& e : fs::directory_iterator(out / "vdb"))
        entries += e.is_regular_file() ? 1 : 0;
    EXPECT_EQ(entries, 1u);

    const auto read = readBack(path);
    ASSERT_TRUE(read);
    EXPECT_EQ(read->getName(), "density");
    EXPECT_EQ(read->getGridClass(), openvdb::GRID_FOG_VOLUME);
    EXPECT_EQ(read->voxelSize(), openvdb::Vec3d(1.0));
    EXPECT_EQ(read->metaValue<openvdb::Int32>("frame"), 42);
    EXPECT_EQ(read->metaValue<std::string>("units"), "metres");
    EXPECT_EQ(read->activeVoxelCount(), grid->activeVoxelCount());
    auto acc = read->getConstAccessor();
    std::size_t mismatches = 0;
    for (auto it = grid->tree().cbeginValueOn(); it; ++it)
        mismatches += !acc.isValueOn(it.getCoord()) || acc.getValue(it.getCoord()) != *it;
    EXPECT_EQ(mismatches, 0u);
    EXPECT_GT(grid->activeVoxelCount(), 1000u);
}

TEST_F(WriteVdbTest, TheSameGridGivesTheSameBytesAndDifferentGridsDifferentUuids)
{
    // OpenVDB's UUID is random per write; ours is derived from the rest of the file.
    const fs::path first = write(parse(R"({"file": "a/cloud.####.vdb"})"), 42);
    const fs::path second = write(parse(R"({"file": "b/cloud.####.vdb"})"), 42);
    const fs::path other = write(parse(R"({"file": "c/cloud.####.vdb"})"), 43);
    EXPECT_EQ(test::readFile(first), test::readFile(second));
    openvdb::io::File a(first.string()), c(other.string());
    a.open();
    c.open();  // OpenVDB parses the UUID on open: ours must be well formed
    EXPECT_FALSE(a.isIdentical(c.getUniqueTag()));
    EXPECT_EQ(a.getUniqueTag().size(), 36u);
    EXPECT_EQ(a.getUniqueTag()[14], '4');  // laid out as a version 4 UUID
    ASSERT_TRUE(readBack(first));
}

TEST_F(WriteVdbTest, HalfFloatIsSmallerAndClose)
{
    const fs::path full = write(parse(R"({"file": "full.####.vdb", "compression": "none"})"), 1);
    openvdb::FloatGrid::ConstPtr grid;
    const fs::path half = write(
        parse(R"({"file": "half.####.vdb", "compression": "none", "halfFloat": true})"), 1, &grid);
    EXPECT_LT(fs::file_size(half), fs::file_size(full) * 3 / 4);
    const auto read = readBack(half);
    ASSERT_EQ(read->activeVoxelCount(), grid->activeVoxelCount());
    auto acc = read->getConstAccessor();
    double worst = 0.0;
    for (auto it = grid->tree().cbeginValueOn(); it; ++it)
        worst = std::max(worst, std::fabs(double(acc.getValue(it.getCoord())) - *it) / *it);
    EXPECT_LT(worst, 1e-3);  // half: 11-bit significand
}

TEST_F(WriteVdbTest, CompressionShrinksTheFileAndReadsBack)
{
    EXPECT_TRUE(openvdb::io::Archive::hasBloscCompression())
        << "Debian's OpenVDB 10 is built with Blosc; 'auto' falls back to zip without it";
    const fs::path none = write(parse(R"({"file": "none.####.vdb", "compression": "none"})"), 3);
    for (const std::string c : {"auto", "blosc", "zip"}) {
        const fs::path p =
            write(parse(R"({"file": ")" + c + R"(.####.vdb", "compression": ")" + c + R"("})"), 3);
        EXPECT_LT(fs::file_size(p), fs::file_size(none)) << c;
        EXPECT_EQ(readBack(p)->activeVoxelCount(), readBack(none)->activeVoxelCount()) << c;
    }
}

TEST_F(WriteVdbTest, EveryNthFrameOnly)
{
    const Graph g = parse(R"({"file": "e.####.vdb", "every": 2})");
    EXPECT_FALSE(write(g, 0).empty());
    EXPECT_TRUE(write(g, 1).empty());
    EXPECT_TRUE(fs::exists(out / "e.0000.vdb"));
    EXPECT_FALSE(fs::exists(out / "e.0001.vdb"));
}

TEST_F(WriteVdbTest, EmptyGridsAreNotWrittenSoTheSequenceStartsWithTheCloud)
{
    const Graph g = parseGrowing(R"({"file": "s/density.####.vdb"})");
    std::vector<int> expected;
    for (int f = 3; f <= 20; ++f) expected.push_back(f);
    EXPECT_EQ(writtenFrames(g), expected);
    EXPECT_FALSE(fs::exists(out / "s/density.0002.vdb"));
    // The first file holds the cloud: consecutive numbers from there, as Blender wants.
    EXPECT_EQ(readBack(out / "s/density.0003.vdb")->activeVoxelCount(), 25u * 4u);
}

TEST_F(WriteVdbTest, SkipEmptyOffWritesTheEmptyGrid)
{
    const Graph g = parseGrowing(R"({"file": "e/density.####.vdb", "skipEmpty": false})");
    const fs::path path = write(g, 0);
    EXPECT_EQ(path, out / "e/density.0000.vdb");
    EXPECT_EQ(readBack(path)->activeVoxelCount(), 0u);
}

TEST_F(WriteVdbTest, EveryCountsFromFirstFrame)
{
    // The default run's case: every 100 from the start wrote an empty frame 0. With firstFrame
    // on the cloud's first frame the first file holds the cloud.
    const Graph onCloud = parseGrowing(R"({"file": "a/d.####.vdb", "every": 4, "firstFrame": 3})");
    EXPECT_EQ(writtenFrames(onCloud), (std::vector<int>{3, 7, 11, 15, 19}));
    // From the start frame, the empty frame 0 is skipped and the schedule is kept.
    EXPECT_EQ(writtenFrames(parseGrowing(R"({"file": "b/d.####.vdb", "every": 4})")),
              (std::vector<int>{4, 8, 12, 16, 20}));
    // A firstFrame before the cloud: its empty frames are skipped, the schedule is kept.
    const Graph early = parseGrowing(R"({"file": "c/d.####.vdb", "every": 5, "firstFrame": 1})");
    EXPECT_EQ(writtenFrames(early), (std::vector<int>{6, 11, 16}));
}

TEST_F(WriteVdbTest, WhichFramesAreWrittenDoesNotDependOnWhatWasCookedBefore)
{
    // One evaluator cooking 0..20 in order writes the same frames as fresh ones per frame.
    const Graph g = parseGrowing(R"({"file": "d/d.####.vdb", "every": 4, "firstFrame": 3})");
    EvaluatorOptions options;
    options.outDir = out.path();
    Evaluator ev(registry, options);
    std::vector<int> inOrder;
    for (int f = 0; f <= 20; ++f) {
        const auto files =
            std::dynamic_pointer_cast<const TextData>(ev.pull(g, "write", f)->at("files"));
        if (files && !files->value.empty()) inOrder.push_back(f);
    }
    EXPECT_EQ(inOrder, writtenFrames(g));
}

TEST_F(WriteVdbTest, VdbPrintReadsTheWrittenFile)
{
    const std::string vdbPrint = test::findOnPath("vdb_print");
    ASSERT_FALSE(vdbPrint.empty())
        << "vdb_print is not on PATH: install the Debian package libopenvdb-tools "
           "(scripts/install-deps.sh lists it); this test needs it and does not skip";
    const fs::path path = write(parse(R"({"file": "print.####.vdb"})"), 5);
    const test::ProgramResult run =
        test::runProgram({vdbPrint, path.string(), "-l", "-m"}, out / "vdb_print.log");
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("density"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("fog volume"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("creator"), std::string::npos) << run.output;
    // The active voxel count it reports is ours.
    const auto grid = readBack(path);
    EXPECT_NE(run.output.find(std::to_string(grid->activeVoxelCount())), std::string::npos)
        << run.output;
}

}  // namespace cg
