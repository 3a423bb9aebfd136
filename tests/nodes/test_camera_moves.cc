// Camera moves through the Renderer (cameraKeys, cameraFile) and out of it (WriteCamera's .chan,
// the EXR's camera attributes): keys render as the static camera, bit for bit; a .chan written
// and read back gives the same camera on every frame; the EXR's worldToNDC puts a point on the
// pixel the Renderer's ray went through; bad keys and files are refused naming them.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "algo/render/CameraMatrices.h"
#include "algo/render/RenderRays.h"
#include "core/Error.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Registry.h"
#include "formats/ChanFile.h"
#include "formats/ExrFile.h"
#include "nodes/data/DataTypes.h"
#include "nodes/data/Image.h"
#include "nodes/render/RenderNodes.h"
#include "support/FixtureNodes.h"
#include "support/TestUtil.h"

namespace cg {

namespace {

// Three keys: a dolly in and a crane up with a zoom.
const char* kKeys = R"([0, 0, -5000, 900, 0, 0, 1300, 40,
                        5, 600, -4200, 1100, 100, 0, 1400, 34,
                        9, 900, -3000, 1500, 0, 50, 1300, 47])";

class CameraMovesTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        registerCoreDataTypes(registry);
        registerNodeDataTypes(registry);
        registerFixtureNodes(registry);
        registerSyntheticCumulusNode(registry);
        registerRendererNode(registry);
        registerWriteImageNode(registry);
        registerWriteCameraNode(registry);
        registerWriteShotNode(registry);
    }

    /// A small cumulus seen by a Renderer with `renderParams`, frames 0-9, and `extra` nodes.
    Graph scene(const std::string& renderParams, const std::string& extra = "")
    {
        return parseGraph(R"({"cloudgraph": 1, "frames": {"start": 0, "end": 9}, "nodes": {
            "cloud": {"type": "SyntheticCumulus", "params": {"voxelSize": 40, "levels": 3}},
            "render": {"type": "Renderer", "inputs": {"volume": "cloud.volume"},
                       "params": {"width": 40, "height": 24, )" +
                              renderParams + "}}" + extra + "}}",
                          (out / "shot.json").string(), registry);
    }

    std::shared_ptr<const ImageData> image(const Graph& g, int frame)
    {
        EvaluatorOptions options;
        options.outDir = out.path();
        Evaluator ev(registry, options);
        return std::dynamic_pointer_cast<const ImageData>(ev.pull(g, "render", frame)->at("image"));
    }

    test::TempDir out;
    Registry registry;
};

/// The static camera params of key `i` of kKeys.
std::string staticCamera(const std::vector<double>& k)
{
    const auto v = [](double a, double b, double c) {
        return "[" + std::to_string(a) + ", " + std::to_string(b) + ", " + std::to_string(c) + "]";
    };
    return R"("cameraPosition": )" + v(k[1], k[2], k[3]) + R"(, "cameraLookAt": )" +
           v(k[4], k[5], k[6]) + R"(, "fov": )" + std::to_string(k[7]);
}

}  // namespace

TEST_F(CameraMovesTest, EachKeyRendersAsTheStaticCameraSetToItBitForBit)
{
    const Graph moving = scene(std::string(R"("cameraKeys": )") + kKeys);
    const std::vector<std::vector<double>> keys = {{0, 0, -5000, 900, 0, 0, 1300, 40},
                                                   {5, 600, -4200, 1100, 100, 0, 1400, 34},
                                                   {9, 900, -3000, 1500, 0, 50, 1300, 47}};
    for (const auto& k : keys) {
        const int frame = static_cast<int>(k[0]);
        const auto keyed = image(moving, frame);
        const auto still = image(scene(staticCamera(k)), frame);
        EXPECT_EQ(keyed->rgba, still->rgba) << "frame " << frame;
        ASSERT_TRUE(keyed->camera);
        EXPECT_EQ(keyed->camera->fovDegrees, k[7]);
    }
    // Between keys the camera is elsewhere: the picture differs from both neighbours.
    const auto between = image(moving, 3);
    EXPECT_NE(between->rgba, image(moving, 0)->rgba);
    EXPECT_NE(between->rgba, image(moving, 5)->rgba);
    EXPECT_GT(between->camera->position.x(), 0.0);
    EXPECT_LT(between->camera->position.x(), 600.0);
}

TEST_F(CameraMovesTest, OnlyAMovingCameraMakesAStillCloudRenderOnEveryFrame)
{
    // The synthetic cumulus does not change with the frame: a still camera's render is one
    // cache entry for the whole shot, a moving camera's one a frame.
    Evaluator ev(registry, {});
    const Graph still = scene(R"("cameraPosition": [0, -5000, 900])");
    EXPECT_EQ(ev.key(still, "render", 0), ev.key(still, "render", 7));
    const Graph moving = scene(std::string(R"("cameraKeys": )") + kKeys);
    EXPECT_NE(ev.key(moving, "render", 0), ev.key(moving, "render", 7));
}

TEST_F(CameraMovesTest, AChanWrittenAndReadBackGivesTheSameCameraOnEveryFrame)
{
    const Graph writing = scene(std::string(R"("cameraKeys": )") + kKeys,
                                R"(, "chan": {"type": "WriteCamera", "inputs": {"camera":
                                   "render.camera"}, "params": {"file": "cam/shot.chan"}})");
    EvaluatorOptions options;
    options.outDir = out.path();
    Evaluator ev(registry, options);
    ev.cookFrames(writing, 4, 4);  // any one frame writes the whole shot
    const std::filesystem::path chan = out / "cam/shot.chan";
    const std::vector<formats::ChanLine> lines = formats::readChan(chan);
    ASSERT_EQ(lines.size(), 10u);
    EXPECT_EQ(lines.front().frame, 0);
    EXPECT_EQ(lines.back().frame, 9);

    const Graph reading = scene(R"("cameraFile": ")" + chan.string() + R"(")");
    for (int frame = 0; frame <= 9; ++frame) {
        const algo::RenderCamera a = *image(writing, frame)->camera;
        const algo::RenderCamera b = *image(reading, frame)->camera;
        EXPECT_LT((a.position - b.position).length(), 1e-6) << frame;
        const algo::CameraRays ra(a), rb(b);
        for (int px : {0, 39})
            for (int py : {0, 23})
                EXPECT_LT((ra.direction(px, py) - rb.direction(px, py)).length(), 1e-9) << frame;
        EXPECT_NEAR(a.fovDegrees, b.fovDegrees, 1e-12);
    }
}

// WriteShot: the camera of every frame of the graph's range as the Renderer has it, the
// frame time, and the lighting with the volume's optics; a text that is not the Renderer's
// lighting is refused naming the port.
TEST_F(CameraMovesTest, TheShotHoldsEveryFramesCameraAndTheLightingTheRendererUsed)
{
    Graph g = scene(std::string(R"("cameraKeys": )") + kKeys + R"(, "sunIntensity": 17)",
                    R"(, "shot": {"type": "WriteShot", "inputs": {"camera":
                             "render.camera", "lighting": "render.lighting"},
                             "params": {"file": "cam/shot.json"}})");
    g.timeStep = 2.5;
    EvaluatorOptions options;
    options.outDir = out.path();
    Evaluator ev(registry, options);
    ev.cookFrames(g, 3, 3);  // any one frame writes the whole shot
    const nlohmann::json shot = nlohmann::json::parse(test::readFile(out / "cam/shot.json"));
    EXPECT_EQ(shot["cloudgraph_shot"], 1);
    EXPECT_EQ(shot["frames"]["start"], 0);
    EXPECT_EQ(shot["frames"]["end"], 9);
    EXPECT_EQ(shot["frame_time_s"], 2.5);
    EXPECT_EQ(shot["image"]["width"], 40);
    ASSERT_EQ(shot["camera"].size(), 10u);
    for (int frame = 0; frame <= 9; ++frame) {
        const algo::RenderCamera c = *image(g, frame)->camera;
        const nlohmann::json& k = shot["camera"][static_cast<std::size_t>(frame)];
        EXPECT_EQ(k["frame"], frame);
        for (int a = 0; a < 3; ++a) {
            EXPECT_EQ(k["position"][a].get<double>(), c.position[a]) << frame;
            EXPECT_EQ(k["look_at"][a].get<double>(), c.lookAt[a]) << frame;
        }
        EXPECT_EQ(k["vertical_fov_deg"].get<double>(), c.fovDegrees) << frame;
    }
    const nlohmann::json& light = shot["lighting"];
    EXPECT_EQ(light["sun"]["irradiance"], 17.0);
    double norm = 0.0;
    for (int a = 0; a < 3; ++a) norm += std::pow(light["sun"]["direction"][a].get<double>(), 2);
    EXPECT_NEAR(norm, 1.0, 1e-12);
    // The default two-lobe phase: (1 - 0.2) 0.8 + 0.2 (-0.3).
    EXPECT_NEAR(light["medium"]["mean_cosine"].get<double>(), 0.58, 1e-12);

    const Graph bad = parseGraph(R"({"cloudgraph": 1, "frames": {"start": 0, "end": 2}, "nodes": {
        "camera": {"type": "TestCameraSource"}, "text": {"type": "TestTextSource"},
        "shot": {"type": "WriteShot", "inputs": {"camera": "camera.camera",
                 "lighting": "text.value"}}}})",
                                 "bad.json", registry);
    try {
        ev.cookFrames(bad, 0, 0);
        ADD_FAILURE() << "a text was written as the lighting";
    } catch (const CookError& e) {
        EXPECT_TRUE(e.inputFault());
        EXPECT_NE(std::string(e.what()).find("not a JSON object"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(out / "shot.json"));
}

TEST_F(CameraMovesTest, TheExrsCameraPutsAPointOnThePixelTheRendererShotItThrough)
{
    const Graph g = scene(std::string(R"("cameraKeys": )") + kKeys,
                          R"(, "exr": {"type": "WriteImage", "inputs": {"image": "render.image"},
                                "params": {"file": "img/frame.####.exr"}})");
    EvaluatorOptions options;
    options.outDir = out.path();
    Evaluator ev(registry, options);
    ev.cookFrames(g, 3, 3);
    const auto camera = formats::readExrCamera((out / "img/frame.0003.exr").string());
    ASSERT_TRUE(camera);
    algo::Matrix44 ndc{};
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) ndc[r][c] = camera->worldToNDC[r][c];
    const algo::RenderCamera used = *image(g, 3)->camera;
    const algo::CameraRays rays(used);
    for (int px : {0, 13, 39})
        for (int py : {0, 11, 23}) {
            double at[2];
            algo::projectToNdc(ndc, used.position + rays.direction(px, py) * 4000.0, at);
            EXPECT_NEAR(at[0] * used.width - 0.5, px, 0.05);  // float matrices
            EXPECT_NEAR(at[1] * used.height - 0.5, py, 0.05);
        }
}

TEST_F(CameraMovesTest, BadKeysAndCameraFilesAreRefusedAtLoadNamingThem)
{
    const auto refusal = [&](const std::string& params) -> std::string {
        try {
            scene(params);
        } catch (const InputError& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_NE(refusal(R"("cameraKeys": [0, 0, -5000, 900, 0, 0, 1300])").find("cameraKeys"),
              std::string::npos);
    EXPECT_NE(refusal(R"("cameraKeys": [0, 0, -5000, 900, 0, 0, 1300, 40,
                                         0, 0, -4000, 900, 0, 0, 1300, 40])")
                  .find("camera key 1"),
              std::string::npos);
    std::ofstream(out / "bad.chan") << "1 0 0 0 0 0 0 40\n2 0 0 0 0 0\n";
    const std::string bad = refusal(R"("cameraFile": ")" + (out / "bad.chan").string() + "\"");
    EXPECT_NE(bad.find("cameraFile"), std::string::npos) << bad;
    EXPECT_NE(bad.find("bad.chan:2"), std::string::npos) << bad;
}

}  // namespace cg
