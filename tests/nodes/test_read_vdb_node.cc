// ReadVDB: what WriteVDB writes reads back voxel for voxel (full and half floats); the key is
// the file's content; a file that cannot be read as a fog volume is refused when the graph is
// loaded, naming the node's parameter, the file and the grid.

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>

#include <openvdb/io/File.h>
#include <openvdb/tools/LevelSetSphere.h>

#include "core/CoreData.h"
#include "core/Data.h"
#include "core/Error.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Registry.h"
#include "nodes/Builtin.h"
#include "nodes/data/FogVolume.h"
#include "nodes/data/Image.h"
#include "support/FixtureNodes.h"
#include "support/TestUtil.h"

namespace cg {

namespace {

namespace fs = std::filesystem;

class ReadVdbTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        registerBuiltinNodes(registry);
        registerFixtureNodes(registry);
    }

    /// A voxelized ball written by WriteVDB to `file` under out/; the voxelizer's grid.
    openvdb::FloatGrid::ConstPtr writeCloud(const std::string& file, bool half)
    {
        const Graph g =
            parseGraph(R"({"cloudgraph": 1, "nodes": {
            "cloud": {"type": "TestCloudSource", "params": {"radius": 25, "spacing": 2}},
            "vox": {"type": "Voxelizer", "inputs": {"particles": "cloud.particles"},
                    "params": {"voxelSize": 1.5, "radius": 3.0, "density": 0.3}},
            "write": {"type": "WriteVDB", "inputs": {"volume": "vox.volume"},
                      "params": {"file": ")" +
                           file + R"(", "halfFloat": )" + (half ? "true" : "false") + "}}}}",
                       "write.json", registry);
        EvaluatorOptions options;
        options.outDir = out.path();
        Evaluator ev(registry, options);
        ev.pull(g, "write", 0);
        return std::dynamic_pointer_cast<const FogVolumeData>(ev.pull(g, "vox", 0)->at("volume"))
            ->grid;
    }

    Graph readGraph(const fs::path& file, const std::string& grid = "density",
                    const LoadOptions& options = {})
    {
        return parseGraph(R"({"cloudgraph": 1, "nodes": {
            "read": {"type": "ReadVDB", "params": {"file": ")" +
                              file.string() + R"(", "grid": ")" + grid + R"("}}}})",
                          "read.json", registry, options);
    }

    openvdb::FloatGrid::ConstPtr read(const fs::path& file)
    {
        Evaluator ev(registry, {});
        const auto volume = std::dynamic_pointer_cast<const FogVolumeData>(
            ev.pull(readGraph(file), "read", 0)->at("volume"));
        return volume ? volume->grid : nullptr;
    }

    /// The message of the InputError loading a ReadVDB graph of `file` throws.
    std::string loadRefusal(const fs::path& file, const std::string& grid = "density",
                            const LoadOptions& options = {}, bool namesGrid = true)
    {
        try {
            readGraph(file, grid, options);
        } catch (const InputError& e) {
            EXPECT_EQ(e.where(), "read.json:/nodes/read/params/file") << e.what();
            EXPECT_NE(e.message().find(file.string()), std::string::npos) << e.what();
            if (namesGrid) {
                EXPECT_NE(e.message().find("grid '" + grid + "'"), std::string::npos) << e.what();
            }
            return e.message();
        }
        ADD_FAILURE() << file << " was accepted at load";
        return "";
    }

    Registry registry;
    test::TempDir out;
};

/// Voxels of `a` that `b` lacks or holds another value or state at (tiles expanded).
std::size_t differences(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b, bool half = false)
{
    std::size_t n = 0;
    auto acc = b.getConstAccessor();
    for (auto it = a.cbeginValueOn(); it; ++it) {
        const float expected = half ? float(openvdb::math::half(*it)) : *it;
        openvdb::CoordBBox box;
        it.getBoundingBox(box);
        for (auto c = box.begin(); c; ++c) n += !acc.isValueOn(*c) || acc.getValue(*c) != expected;
    }
    return n;
}

}  // namespace

TEST_F(ReadVdbTest, RoundTripsWhatWriteVdbWritesVoxelForVoxel)
{
    for (const bool half : {false, true}) {
        const std::string file = half ? "half.vdb" : "full.vdb";
        const auto written = writeCloud(file, half);
        ASSERT_GT(written->activeVoxelCount(), 1000u);
        const auto back = read(out / file);
        ASSERT_TRUE(back) << file;
        EXPECT_EQ(back->getName(), "density");
        EXPECT_EQ(back->getGridClass(), openvdb::GRID_FOG_VOLUME);
        EXPECT_EQ(back->transform(), written->transform()) << file;
        EXPECT_EQ(back->background(), 0.0f);
        EXPECT_EQ(back->activeVoxelCount(), written->activeVoxelCount()) << file;
        EXPECT_EQ(differences(*written, *back, half), 0u) << file;
        EXPECT_EQ(differences(*back, *written, false) == 0u, !half) << file;
        EXPECT_EQ(back->tree().activeTileCount(), written->tree().activeTileCount());
        // What the Voxelizer records stays.
        EXPECT_EQ(back->metaValue<std::string>("units"), "metres");
        // And it is a value the disk cache can store.
        ByteWriter bytes;
        EXPECT_TRUE(FogVolumeData(back).serialize(bytes)) << file;
    }
}

TEST_F(ReadVdbTest, TheKeyIsTheFilesContentNotItsPath)
{
    writeCloud("a.vdb", false);
    fs::copy_file(out / "a.vdb", out / "b.vdb");
    Evaluator ev(registry, {});
    const Key a = ev.key(readGraph(out / "a.vdb"), "read", 0);
    EXPECT_EQ(Evaluator(registry, {}).key(readGraph(out / "b.vdb"), "read", 0), a);

    // Another content under the same name: another key, and a recook that reads it.
    writeCloud("c.vdb", true);
    fs::rename(out / "c.vdb", out / "a.vdb");
    const Graph g = readGraph(out / "a.vdb");
    Evaluator fresh(registry, {});
    EXPECT_NE(fresh.key(g, "read", 0), a);
    const auto grid =
        std::dynamic_pointer_cast<const FogVolumeData>(fresh.pull(g, "read", 0)->at("volume"));
    const auto full = read(out / "b.vdb");
    EXPECT_GT(differences(*full, *grid->grid), 0u);  // the half-float values
}

TEST_F(ReadVdbTest, BadFilesAreRefusedAtLoadNamingTheFileAndGrid)
{
    writeCloud("good.vdb", false);
    EXPECT_NE(loadRefusal(out / "good.vdb", "smoke").find("its grids: 'density' (float)"),
              std::string::npos);
    // The engine checks every input file first: a missing one is refused before the reader.
    EXPECT_NE(loadRefusal(out / "missing.vdb", "density", {}, false).find("cannot open"),
              std::string::npos);

    auto sphere = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(10.0f, {}, 1.0f);
    sphere->setName("density");
    openvdb::io::File((out / "ls.vdb").string()).write({sphere});
    EXPECT_NE(loadRefusal(out / "ls.vdb").find("level set"), std::string::npos);

    const std::string bytes = test::readFile(out / "good.vdb");
    test::writeFile(out / "cut.vdb", bytes.substr(0, bytes.size() / 2));
    EXPECT_NE(loadRefusal(out / "cut.vdb").find("truncated"), std::string::npos);

    LoadOptions small;  // room for the file, not for the grid it records
    small.allocationLimitBytes = bytes.size() + 64;
    EXPECT_NE(loadRefusal(out / "good.vdb", "density", small).find("more than"), std::string::npos);
}

namespace {

/// The image of a 48 x 32 render of the VDB `file` with the given Renderer parameters (JSON).
std::vector<float> renderOf(Registry& registry, const fs::path& file, const std::string& params)
{
    const Graph g = parseGraph(R"({"cloudgraph": 1, "nodes": {
        "read": {"type": "ReadVDB", "params": {"file": ")" +
                                   file.string() + R"("}},
        "render": {"type": "Renderer", "inputs": {"volume": "read.volume"},
                   "params": {"width": 48, "height": 32, "cameraPosition": [0, -400, 30],
                              "cameraLookAt": [0, 0, 30], )" +
                                   params + "}}}}",
                               "render.json", registry);
    Evaluator ev(registry, {});
    return std::dynamic_pointer_cast<const ImageData>(ev.pull(g, "render", 0)->at("image"))->rgba;
}

/// A 40 m cube of density 0.5 on 2 m voxels, with `meta` float metadata.
void writeCube(const fs::path& file, const std::vector<std::pair<std::string, float>>& meta)
{
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(2.0));
    grid->denseFill(openvdb::CoordBBox(openvdb::Coord(-10, -10, 5), openvdb::Coord(9, 9, 24)), 0.5f,
                    true);
    for (const auto& [name, value] : meta) grid->insertMeta(name, openvdb::FloatMetadata(value));
    openvdb::io::File(file.string()).write({grid});
}

}  // namespace

TEST_F(ReadVdbTest, TheVolumesOpticsReplaceTheRenderersParametersUnlessTurnedOff)
{
    // Values a float holds exactly: the metadata is float, the parameters double.
    writeCube(out.path() / "water.vdb", {{"extinction", 0.0625f}, {"albedo", 0.9375f}});
    writeCube(out.path() / "plain.vdb", {});
    const auto fromVolume = renderOf(registry, out.path() / "water.vdb", R"("extinction": 0.01)");
    EXPECT_EQ(fromVolume, renderOf(registry, out.path() / "plain.vdb",
                                   R"("extinction": 0.0625, "albedo": 0.9375)"));
    EXPECT_NE(fromVolume, renderOf(registry, out.path() / "water.vdb",
                                   R"("extinction": 0.01, "volumeOptics": false)"));
    writeCube(out.path() / "bad.vdb", {{"albedo", 1.5f}});
    try {
        renderOf(registry, out.path() / "bad.vdb", R"("extinction": 0.01)");
        ADD_FAILURE() << "an albedo of 1.5 was taken";
    } catch (const CookError& e) {
        EXPECT_NE(std::string(e.what()).find("'albedo' metadata"), std::string::npos) << e.what();
    }
}

}  // namespace cg
