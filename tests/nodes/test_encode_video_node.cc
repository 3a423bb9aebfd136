// EncodeVideo: PNG frames written by WriteImage become an H.264 MP4 (checked by its ftyp box
// and by ffprobe when installed); a missing ffmpeg or a missing frame gives a clear error.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Registry.h"
#include "formats/VideoEncode.h"
#include "nodes/data/DataTypes.h"
#include "nodes/io/IoNodes.h"
#include "nodes/render/RenderNodes.h"
#include "support/FixtureNodes.h"
#include "support/TestUtil.h"
#include "util/FramePattern.h"

namespace cg {

namespace {

namespace fs = std::filesystem;

class EncodeVideoTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        registerCoreDataTypes(registry);
        registerNodeDataTypes(registry);
        registerFixtureNodes(registry);
        registerWriteImageNode(registry);
        registerEncodeVideoNode(registry);
    }

    /// A 33 x 17 ramp (odd sizes: the encoder pads them) written as frames/f.####.png and
    /// encoded on frame 3 from frame 0.
    Graph parse(const std::string& videoParams, const LoadOptions& options = {})
    {
        return parseGraph(R"({"cloudgraph": 1, "nodes": {
            "ramp": {"type": "TestImageSource", "params": {"width": 33, "height": 17}},
            "write": {"type": "WriteImage", "inputs": {"image": "ramp.image"},
                      "params": {"file": "frames/f.####.png"}},
            "video": {"type": "EncodeVideo", "inputs": {"frames": "write.files"},
                      "params": )" +
                              videoParams + "}}}",
                          "test.json", registry, options);
    }

    Evaluator evaluator()
    {
        EvaluatorOptions options;
        options.outDir = out.path();
        return Evaluator(registry, options);
    }

    Registry registry;
    test::TempDir out;
};

const char* kParams = R"({"file": "video/v.mp4", "images": "frames/f.####.png",
                          "firstFrame": 0, "lastFrame": 3, "fps": 12, "crf": 30)";

std::size_t filesIn(const fs::path& dir)
{
    std::size_t n = 0;
    for (const auto& e : fs::directory_iterator(dir)) n += e.is_regular_file();
    return n;
}

}  // namespace

TEST(FramePattern, FramePathReplacesTheFirstHashRunInTheFileName)
{
    EXPECT_EQ(util::framePath("/o/f.####.png", 42), fs::path("/o/f.0042.png"));
    EXPECT_EQ(util::framePath("a_##_b#.png", 7), fs::path("a_07_b#.png"));
    EXPECT_EQ(util::framePath("a_##.png", 1234), fs::path("a_1234.png"));  // never truncated
    EXPECT_EQ(util::framePath("plain.png", 1), fs::path("plain.png"));
    EXPECT_EQ(util::framePath("d#/f.#.png", 3), fs::path("d#/f.3.png"));
}

TEST(FramePattern, OutputFileProblemsAreNamed)
{
    EXPECT_EQ(util::outputFileProblem("frames/f.####.png"), "");
    EXPECT_EQ(util::outputFileProblem("f.#########.png"), "");  // 9: the most allowed
    EXPECT_NE(util::outputFileProblem("f." + std::string(10, '#') + ".png"), "");
    EXPECT_NE(util::outputFileProblem("f." + std::string(32, '#') + ".png"), "");
    EXPECT_NE(util::outputFileProblem("dir/"), "");
    EXPECT_NE(util::outputFileProblem("."), "");
    EXPECT_NE(util::outputFileProblem("a/.."), "");
    EXPECT_NE(util::outputFileProblem(""), "");
    EXPECT_NE(util::outputFileProblem("d##/f.png"), "");
}

TEST_F(EncodeVideoTest, EncodesTheWrittenFramesIntoAnMp4)
{
    if (test::findOnPath("ffmpeg").empty()) GTEST_SKIP() << "ffmpeg is not installed";
    const Graph g = parse(std::string(kParams) + "}");
    Evaluator ev = evaluator();
    ev.cookFrames(g, 0, 3);
    const fs::path mp4 = out / "video/v.mp4";
    ASSERT_TRUE(fs::is_regular_file(mp4));
    EXPECT_EQ(filesIn(out / "video"), 1u);  // no temp file or log left beside it
    // An MP4 starts with its ftyp box: 4 bytes of size, then "ftyp".
    const std::string bytes = test::readFile(mp4);
    ASSERT_GT(bytes.size(), 8u);
    EXPECT_EQ(bytes.substr(4, 4), "ftyp");

    const std::string ffprobe = test::findOnPath("ffprobe");
    if (ffprobe.empty()) return;
    const test::ProgramResult run = test::runProgram(
        {ffprobe, "-v", "error", "-select_streams", "v:0", "-count_frames", "-show_entries",
         "stream=codec_name,pix_fmt,width,height,nb_read_frames,color_space,"
         "color_primaries,color_transfer,color_range",
         "-of", "default=noprint_wrappers=1", mp4.string()},
        out / "ffprobe.log", /*alsoStderr=*/false);
    const std::string& probe = run.output;
    ASSERT_EQ(run.status, 0) << probe;
    EXPECT_NE(probe.find("codec_name=h264"), std::string::npos) << probe;
    EXPECT_NE(probe.find("pix_fmt=yuv420p"), std::string::npos) << probe;
    EXPECT_NE(probe.find("width=34"), std::string::npos) << probe;  // padded to even
    EXPECT_NE(probe.find("height=18"), std::string::npos) << probe;
    EXPECT_NE(probe.find("nb_read_frames=4"), std::string::npos) << probe;
    // Tagged as what it holds: Rec.709 primaries and matrix, the sRGB curve, video range.
    EXPECT_NE(probe.find("color_space=bt709"), std::string::npos) << probe;
    EXPECT_NE(probe.find("color_primaries=bt709"), std::string::npos) << probe;
    EXPECT_NE(probe.find("color_transfer=iec61966-2-1"), std::string::npos) << probe;
    EXPECT_NE(probe.find("color_range=tv"), std::string::npos) << probe;
}

TEST_F(EncodeVideoTest, OnlyTheLastFrameEncodes)
{
    const Graph g = parse(std::string(kParams) + "}");
    Evaluator ev = evaluator();
    const auto files =
        std::dynamic_pointer_cast<const TextData>(ev.pull(g, "video", 1)->at("files"));
    ASSERT_TRUE(files);
    EXPECT_EQ(files->value, "");
    EXPECT_FALSE(fs::exists(out / "video/v.mp4"));
}

/// Sets an environment variable for one scope.
class ScopedEnvironment {
public:
    ScopedEnvironment(const char* name, const char* value) : mName(name)
    {
        if (const char* old = std::getenv(name)) mOld = old;
        ::setenv(name, value, 1);
    }
    ~ScopedEnvironment()
    {
        if (mOld)
            ::setenv(mName, mOld->c_str(), 1);
        else
            ::unsetenv(mName);
    }

private:
    const char* mName;
    std::optional<std::string> mOld;
};

TEST_F(EncodeVideoTest, AGraphMayNotNameTheProgramItRunsUnlessTheUserAllowsIt)
{
    const std::string params = std::string(kParams) + R"(, "ffmpeg": "./script.sh"})";
    try {
        parse(params);
        FAIL() << "a graph that names a program was accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(e.where(), "test.json:/nodes/video/params/ffmpeg");
        EXPECT_NE(e.message().find("--allow-graph-programs"), std::string::npos) << e.what();
    }
    LoadOptions trusted;
    trusted.allowGraphPrograms = true;
    EXPECT_NO_THROW(parse(params, trusted));
    EXPECT_NO_THROW(parse(std::string(kParams) + R"(, "ffmpeg": "ffmpeg"})"));  // the default
}

TEST_F(EncodeVideoTest, MissingFfmpegSaysHowToInstallIt)
{
    const ScopedEnvironment program("CLOUDGRAPH_FFMPEG", "/nonexistent/cloudgraph-test-ffmpeg");
    const Graph g = parse(std::string(kParams) + "}");
    Evaluator ev = evaluator();
    try {
        ev.cookFrames(g, 0, 3);
        FAIL() << "expected an error";
    } catch (const CookError& e) {
        const std::string what = e.what();
        EXPECT_TRUE(e.inputFault());
        EXPECT_NE(what.find("'video'"), std::string::npos) << what;
        EXPECT_NE(what.find("cloudgraph-test-ffmpeg"), std::string::npos) << what;
        EXPECT_NE(what.find("apt-get install -y ffmpeg"), std::string::npos) << what;
        EXPECT_NE(what.find("CLOUDGRAPH_FFMPEG"), std::string::npos) << what;
    }
    EXPECT_FALSE(fs::exists(out / "video/v.mp4"));
    EXPECT_EQ(filesIn(out / "video"), 0u);
}

TEST_F(EncodeVideoTest, MissingFrameIsNamed)
{
    const Graph g = parse(std::string(kParams) + "}");
    Evaluator ev = evaluator();
    try {
        ev.pull(g, "video", 3);  // only frame 3 was written
        FAIL() << "expected an error";
    } catch (const CookError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("frame 0 is missing"), std::string::npos) << what;
        EXPECT_NE(what.find("f.0000.png"), std::string::npos) << what;
    }
}

}  // namespace cg
