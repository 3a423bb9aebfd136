// WriteImage: 8-bit sRGB PNG read back with libpng; linear OpenEXR read back with OpenEXR,
// with the cloud and background layers of a rendered image.

#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "algo/render/image/Display.h"
#include "algo/render/image/ToneMap.h"
#include "algo/render/integrators/RenderVolume.h"
#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Registry.h"
#include "formats/ExrFile.h"
#include "formats/PngFile.h"
#include "nodes/data/DataTypes.h"
#include "nodes/data/Image.h"
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
        registerSyntheticCumulusNode(registry);
        registerRendererNode(registry);
    }

    /// Renders and writes frame 42 of `scene`; returns the Renderer's image.
    std::shared_ptr<const ImageData> renderScene(const std::string& scene)
    {
        const Graph g = parseGraph(scene, "test.json", registry);
        EvaluatorOptions options;
        options.outDir = out.path();
        Evaluator ev(registry, options);
        ev.cookFrames(g, 42, 42);
        return std::dynamic_pointer_cast<const ImageData>(ev.pull(g, "render", 42)->at("image"));
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
                                "params": )" +
                                       params + "}}}",
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
    const formats::Rgb8Image img =
        write(R"({"file": "frames/cloud.####.png", "toneMap": "clamp", "dither": false})");
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
        const double expected = 255.0 * algo::srgbEncode(algo::toneMap(v, algo::ToneCurve::Aces));
        for (int c = 0; c < 3; ++c)
            EXPECT_LE(std::abs(img.rgb[static_cast<std::size_t>(x) * 3 + c] - expected), 1.5) << x;
    }
}

TEST_F(WriteImageTest, ExrKeepsTheLinearValuesExactly)
{
    // Exposure and tone map are for display: the EXR holds the radiance unchanged.
    cook(R"({"file": "frames/cloud.####.exr", "exposure": 3.0, "toneMap": "aces"})",
         "frames/cloud.0042.exr");
    const formats::ExrRgbaImage img =
        formats::readExrRgba((out / "frames/cloud.0042.exr").string());
    ASSERT_EQ(img.width, 16);
    ASSERT_EQ(img.height, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x) {
            const float* px =
                &img.rgba[4 * (static_cast<std::size_t>(y) * 16 + static_cast<std::size_t>(x))];
            const float v = static_cast<float>(x) / 16.0f;
            ASSERT_EQ(px[0], v) << x << "," << y;
            ASSERT_EQ(px[1], v);
            ASSERT_EQ(px[2], v);
            ASSERT_EQ(px[3], 1.0f);
        }
    // An image without a background: today's file, R, G, B, A only.
    EXPECT_EQ(formats::exrChannelNames((out / "frames/cloud.0042.exr").string()),
              (std::vector<std::string>{"A", "B", "G", "R"}));
    std::size_t count = 0;
    for (const auto& e : std::filesystem::recursive_directory_iterator(out.path()))
        if (e.is_regular_file()) ++count;
    EXPECT_EQ(count, 1u);
}

namespace {

/// A small synthetic cumulus seen from the side, sun from the front right, the ground in the
/// lower half of the picture catching its shadow; written as an EXR.
const char* kRenderedScene = R"({"cloudgraph": 1, "frames": {"start": 42, "end": 42},
    "nodes": {
    "cloud": {"type": "SyntheticCumulus", "params": {"voxelSize": 40, "levels": 3}},
    "render": {"type": "Renderer", "inputs": {"volume": "cloud.volume"},
               "params": {"width": 48, "height": 32, "cameraPosition": [0, -5000, 900],
                          "cameraLookAt": [0, 0, 1300], "jitter": true}},
    "write": {"type": "WriteImage", "inputs": {"image": "render.image"},
              "params": {"file": "cloud.####.exr"}}}})";

}  // namespace

TEST_F(WriteImageTest, ExrOfARenderHoldsBeautyCloudAndBackgroundLayers)
{
    const auto image = renderScene(kRenderedScene);
    ASSERT_TRUE(image);
    ASSERT_TRUE(image->hasBackground());
    const int w = image->width, h = image->height;
    const std::string file = (out / "cloud.0042.exr").string();

    // OpenEXR's layer convention, layer.channel: Nuke and Blender show layers cloud and
    // background beside the default R, G, B, A.
    EXPECT_EQ(
        formats::exrChannelNames(file),
        (std::vector<std::string>{"A", "B", "G", "R", "background.B", "background.G",
                                  "background.R", "cloud.A", "cloud.B", "cloud.G", "cloud.R"}));
    const formats::ExrChannelImage exr =
        formats::readExrChannels(file, {"R", "G", "B", "A", "cloud.R", "cloud.G", "cloud.B",
                                        "cloud.A", "background.R", "background.G", "background.B"});
    ASSERT_EQ(exr.width, w);
    ASSERT_EQ(exr.height, h);

    // The default layer is the beauty, bit for bit, as the RGBA reader sees it.
    const formats::ExrRgbaImage rgba = formats::readExrRgba(file);
    ASSERT_EQ(rgba.rgba.size(), image->rgba.size());
    EXPECT_EQ(std::memcmp(rgba.rgba.data(), image->rgba.data(), rgba.rgba.size() * sizeof(float)),
              0);

    const auto pixels = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
    std::size_t clear = 0, opaque = 0;
    for (std::size_t i = 0; i < pixels; ++i) {
        const float* px = &exr.values[11 * i];
        const float* beauty = px;
        const float* cloud = px + 4;
        const float* background = px + 8;
        for (int c = 0; c < 4; ++c) ASSERT_EQ(beauty[c], image->rgba[4 * i + c]) << i;
        for (int c = 0; c < 3; ++c) ASSERT_EQ(background[c], image->background[3 * i + c]) << i;
        const float alpha = beauty[3];
        ASSERT_EQ(cloud[3], alpha) << i;
        // beauty = cloud + (1 - alpha) background, to the float rounding of the layers.
        for (int c = 0; c < 3; ++c) {
            const double behind = (1.0 - double(alpha)) * double(background[c]);
            const double sum = double(cloud[c]) + behind;
            const double scale =
                std::max({std::abs(double(beauty[c])), double(cloud[c]), std::abs(behind)});
            ASSERT_LE(std::abs(sum - double(beauty[c])), 4.0 * FLT_EPSILON * scale)
                << "pixel " << i << " channel " << c << ": " << beauty[c] << " vs " << cloud[c]
                << " + (1 - " << alpha << ") " << background[c];
            ASSERT_GE(cloud[c], 0.0f) << i;
        }
        if (alpha == 0.0f) {
            ++clear;
            // Nothing in front: no cloud, and the beauty is the background itself.
            for (int c = 0; c < 4; ++c) ASSERT_EQ(cloud[c], 0.0f) << i;
            for (int c = 0; c < 3; ++c) ASSERT_EQ(beauty[c], background[c]) << i;
        }
        if (alpha > 0.99f) ++opaque;
    }
    EXPECT_GT(clear, pixels / 4);  // sky and ground around the cloud
    EXPECT_GT(opaque, 10u);        // and an opaque cloud

    // The top left pixel's ray misses cloud and ground: its background is the sky, exactly.
    algo::RenderCamera camera;
    camera.position = algo::RenderVec3(0, -5000, 900);
    camera.lookAt = algo::RenderVec3(0, 0, 1300);
    camera.width = w;
    camera.height = h;
    const algo::RenderVec3 sky =
        algo::skyRadiance(algo::RenderSky{}, algo::CameraRays(camera).direction(0, 0));
    ASSERT_EQ(exr.values[3], 0.0f);
    EXPECT_EQ(exr.values[8], static_cast<float>(sky.x()));
    EXPECT_EQ(exr.values[9], static_cast<float>(sky.y()));
    EXPECT_EQ(exr.values[10], static_cast<float>(sky.z()));
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

TEST(ExrFile, NamedChannelsRoundTripAndAMissingOneIsNamed)
{
    test::TempDir dir;
    const std::string file = (dir / "layers.exr").string();
    const std::vector<float> rgba = {0.5f, 1.5f, -2.0f, 1.0f, 1e-30f, 3e30f, 0.25f, 0.0f};
    const std::vector<float> extra = {7.0f, 8.0f, 9.0f, 10.0f};
    formats::writeExrFloat32(file, 2, 1,
                             {{{"R", "G", "B", "A"}, rgba}, {{"spare.X", "spare.Y"}, extra}});
    const formats::ExrChannelImage back = formats::readExrChannels(file, {"spare.Y", "A", "R"});
    ASSERT_EQ(back.width, 2);
    ASSERT_EQ(back.height, 1);
    EXPECT_EQ(back.values, (std::vector<float>{8.0f, 1.0f, 0.5f, 10.0f, 0.0f, 1e-30f}));
    EXPECT_EQ(formats::readExrRgba(file).rgba, rgba);
    try {
        formats::readExrChannels(file, {"R", "cloud.R"});
        FAIL() << "a missing channel was read";
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("layers.exr"), std::string::npos) << what;
        EXPECT_NE(what.find("cloud.R"), std::string::npos) << what;
    }
    EXPECT_THROW(formats::writeExrFloat32(
                     file, 2, 1, {{{"R", "G", "B", "A"}, rgba}, {{"R", "spare.Y"}, extra}}),
                 std::invalid_argument);
    EXPECT_THROW(formats::writeExrFloat32(file, 2, 1, {{{"spare.X"}, extra}}),
                 std::invalid_argument);
}

TEST_F(WriteImageTest, ExrOfARenderWithAovsHoldsSunSkyDepthShadowAndChromaticities)
{
    std::string scene = kRenderedScene;
    scene.replace(scene.find(R"("jitter": true)"), 14, R"("jitter": true, "aovs": true)");
    const auto image = renderScene(scene);
    ASSERT_FALSE(image->aovs.empty());
    const std::string file = (out / "cloud.0042.exr").string();
    const std::vector<std::string> names = formats::exrChannelNames(file);
    for (const char* name : {"sun.R", "sun.G", "sun.B", "sky.R", "sky.G", "sky.B", "depth.Z",
                             "shadow.A", "cloud.R", "background.R", "R"})
        EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
    const formats::ExrChannelImage exr = formats::readExrChannels(
        file, {"cloud.R", "cloud.G", "cloud.B", "sun.R", "sun.G", "sun.B", "sky.R", "sky.G",
               "sky.B", "depth.Z", "shadow.A", "cloud.A"});
    // sun + sky = the cloud layer, pixel by pixel, to float rounding; cloud pixels have a
    // depth between the camera's distance to the cloud's near and far sides.
    const auto pixels = static_cast<std::size_t>(exr.width) * static_cast<std::size_t>(exr.height);
    std::size_t cloudy = 0, shadowed = 0;
    for (std::size_t i = 0; i < pixels; ++i) {
        const float* px = &exr.values[12 * i];
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(px[3 + c] + px[6 + c], px[c], 1e-5f * std::max(1.0f, px[c])) << i;
        if (px[11] > 0.01f) {
            ++cloudy;
            EXPECT_GT(px[9], 3000.0f) << i;  // the cloud stands about 5 km away
            EXPECT_LT(px[9], 7000.0f) << i;
        }
        EXPECT_GE(px[10], 0.0f);
        EXPECT_LE(px[10], 1.0f);
        shadowed += px[10] > 0.1f;
    }
    EXPECT_GT(cloudy, 10u);
    EXPECT_GT(shadowed, 0u);  // the cloud's shadow on the ground in view
    // Linear Rec.709 primaries, D65 white, in the header.
    const auto chroma = formats::readExrChromaticities(file);
    ASSERT_TRUE(chroma.has_value());
    const formats::ExrChromaticities rec709 = {0.64f, 0.33f, 0.30f,   0.60f,
                                               0.15f, 0.06f, 0.3127f, 0.3290f};
    for (int k = 0; k < 8; ++k) EXPECT_NEAR((*chroma)[k], rec709[k], 1e-4f) << k;
}

TEST_F(WriteImageTest, AovsFromThePathTracerAreRefusedAtLoadNamingTheParameter)
{
    std::string scene = kRenderedScene;
    scene.replace(scene.find(R"("jitter": true)"), 14,
                  R"("jitter": true, "aovs": true, "mode": "pathtrace")");
    try {
        parseGraph(scene, "test.json", registry);
        FAIL() << "AOVs from the path tracer were accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("/nodes/render/params/aovs"), std::string::npos)
            << e.what();
    }
}

}  // namespace cg
