// WriteImage: 8-bit sRGB PNG read back with libpng; linear OpenEXR read back with OpenEXR.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "algo/render/Display.h"
#include "algo/render/ToneMap.h"
#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Registry.h"
#include "formats/ExrFile.h"
#include "formats/PngFile.h"
#include "nodes/data/DataTypes.h"
#include "nodes/render/RenderNodes.h"
#include "support/FixtureNodes.h"
#include "support/TestUtil.h"

namespace cg {

namespace {

class WriteImageTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        registerCoreDataTypes(registry);
        registerNodeDataTypes(registry);
        registerFixtureNodes(registry);
        registerWriteImageNode(registry);
    }

    /// Cooks frame 42 of TestImageSource (a 16 x 8 ramp v = x / 16) into WriteImage.
    formats::Rgb8Image write(const std::string& params)
    {
        cook(params, "frames/cloud.0042.png");
        return formats::readPngRgb8((out / "frames/cloud.0042.png").string());
    }

    /// Cooks frame 42 into WriteImage and checks that it reports `written` (relative to out).
    void cook(const std::string& params, const std::string& written)
    {
        const Graph g = parseGraph(R"({"cloudgraph": 1, "frames": {"start": 42, "end": 42},
            "nodes": {"src": {"type": "TestImageSource"},
                      "write": {"type": "WriteImage", "inputs": {"image": "src.image"},
                                "params": )" + params + "}}}",
                                   "test.json", registry);
        EvaluatorOptions options;
        options.outDir = out.path();
        Evaluator ev(registry, options);
        ev.cookFrames(g, 42, 42);
        const auto files =
            std::dynamic_pointer_cast<const TextData>(ev.pull(g, "write", 42)->at("files"));
        EXPECT_TRUE(files);
        EXPECT_EQ(files->value, (out / written).string());
    }

    test::TempDir out;
    Registry registry;
};

}  // namespace

TEST_F(WriteImageTest, WritesAnSrgbPngThatReadsBack)
{
    const formats::Rgb8Image img = write(
        R"({"file": "frames/cloud.####.png", "toneMap": "clamp", "dither": false})");
    ASSERT_EQ(img.width, 16);
    ASSERT_EQ(img.height, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x) {
            const double v = static_cast<float>(x) / 16.0f;
            const auto expected = static_cast<int>(std::lround(255.0 * algo::srgbEncode(v)));
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(img.rgb[(static_cast<std::size_t>(y) * 16 + x) * 3 + c], expected)
                    << x << "," << y;
        }
    // Spot values of the sRGB curve: 0 -> 0, 0.5 -> 188.
    EXPECT_EQ(img.rgb[0], 0);
    EXPECT_EQ(img.rgb[8 * 3], 188);
    // Only the PNG: no temp file left behind.
    std::size_t count = 0;
    for (const auto& e : std::filesystem::recursive_directory_iterator(out.path()))
        if (e.is_regular_file()) ++count;
    EXPECT_EQ(count, 1u);
}

TEST_F(WriteImageTest, ExposureToneMapAndDitherStayClose)
{
    // One stop up through ACES with dither: within one code value of the undithered mapping.
    const formats::Rgb8Image img =
        write(R"({"file": "frames/cloud.####.png", "exposure": 1.0, "toneMap": "aces"})");
    ASSERT_EQ(img.width, 16);
    for (int x = 0; x < 16; ++x) {
        const double v = 2.0 * (static_cast<float>(x) / 16.0f);
        const double expected =
            255.0 * algo::srgbEncode(algo::toneMap(v, algo::ToneCurve::Aces));
        for (int c = 0; c < 3; ++c)
            EXPECT_LE(std::abs(img.rgb[static_cast<std::size_t>(x) * 3 + c] - expected), 1.5) << x;
    }
}

TEST_F(WriteImageTest, ExrKeepsTheLinearValuesExactly)
{
    // Exposure and tone map are for display: the EXR holds the radiance unchanged.
    cook(R"({"file": "frames/cloud.####.exr", "exposure": 3.0, "toneMap": "aces"})", "frames/cloud.0042.exr");
    const formats::ExrRgbaImage img =
        formats::readExrRgba((out / "frames/cloud.0042.exr").string());
    ASSERT_EQ(img.width, 16);
    ASSERT_EQ(img.height, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x) {
            const float* px = &img.rgba[4 * (static_cast<std::size_t>(y) * 16 + static_cast<std::size_t>(x))];
            const float v = static_cast<float>(x) / 16.0f;
            ASSERT_EQ(px[0], v) << x << "," << y;
            ASSERT_EQ(px[1], v);
            ASSERT_EQ(px[2], v);
            ASSERT_EQ(px[3], 1.0f);
        }
    std::size_t count = 0;
    for (const auto& e : std::filesystem::recursive_directory_iterator(out.path()))
        if (e.is_regular_file()) ++count;
    EXPECT_EQ(count, 1u);
}

TEST_F(WriteImageTest, AnUnknownExtensionIsRefusedAtLoadNamingTheParameter)
{
    try {
        parseGraph(R"({"cloudgraph": 1, "nodes": {"src": {"type": "TestImageSource"},
            "write": {"type": "WriteImage", "inputs": {"image": "src.image"},
                      "params": {"file": "frames/cloud.####.tif"}}}})",
                   "test.json", registry);
        FAIL() << "a .tif file was accepted";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("/nodes/write/params/file"), std::string::npos) << what;
        EXPECT_NE(what.find(".exr"), std::string::npos) << what;
    }
}

TEST(ExrFile, ReadingAFileThatIsNotExrNamesIt)
{
    test::TempDir dir;
    test::writeFile(dir / "bad.exr", "not an exr");
    try {
        formats::readExrRgba((dir / "bad.exr").string());
        FAIL();
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("bad.exr"), std::string::npos);
    }
}

}  // namespace cg
