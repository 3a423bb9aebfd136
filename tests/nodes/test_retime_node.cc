// Retime: which simulated frame each output frame shows (time-lapse, slow motion, holds, a
// rate that does not divide the span), and the node placing those files numbered as asked,
// refusing before it writes anything when a source is missing.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/CoreData.h"
#include "core/Error.h"
#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Registry.h"
#include "nodes/data/DataTypes.h"
#include "nodes/io/IoNodes.h"
#include "support/FixtureNodes.h"
#include "support/TestUtil.h"
#include "util/FramePattern.h"
#include "util/RetimeSchedule.h"

namespace cg {

namespace {

namespace fs = std::filesystem;
using util::RetimeSpec;
using Frames = std::vector<std::int64_t>;

RetimeSpec spec(std::int64_t first, std::int64_t last, double dt, double rate)
{
    RetimeSpec s;
    s.first = first;
    s.last = last;
    s.secondsPerFrame = dt;
    s.framesPerSecond = rate;
    return s;
}

}  // namespace

TEST(RetimeSchedule, OneFramePerSimulatedFrameIsTheSequenceItself)
{
    EXPECT_EQ(util::retimeSchedule(spec(3, 7, 2.0, 0.5)), (Frames{3, 4, 5, 6, 7}));
}

TEST(RetimeSchedule, ATimeLapseSkipsAndASlowMotionRepeats)
{
    // 0.25 frames per simulated second at 2 s a frame: every second frame.
    EXPECT_EQ(util::retimeSchedule(spec(0, 10, 2.0, 0.25)), (Frames{0, 2, 4, 6, 8, 10}));
    // 1 frame per simulated second at 2 s a frame: each frame twice, the last once.
    EXPECT_EQ(util::retimeSchedule(spec(0, 3, 2.0, 1.0)), (Frames{0, 0, 1, 1, 2, 2, 3}));
}

TEST(RetimeSchedule, EachOutputFrameShowsTheLastSimulatedFrameAtOrBeforeItsTime)
{
    // 2/3 of a frame per simulated frame: frame j is at 1.5 j simulated frames.
    const RetimeSpec s = spec(10, 40, 2.0, 1.0 / 3.0);
    const Frames shows = util::retimeSchedule(s);
    ASSERT_EQ(static_cast<std::int64_t>(shows.size()), util::retimedFrameCount(s));
    EXPECT_EQ(shows.size(), 21u);  // floor(30 x 2/3) + 1
    for (std::size_t j = 0; j < shows.size(); ++j)
        EXPECT_EQ(shows[j], 10 + static_cast<std::int64_t>(std::floor(1.5 * j))) << j;
}

TEST(RetimeSchedule, HoldsRepeatTheEnds)
{
    RetimeSpec s = spec(5, 7, 1.0, 1.0);
    s.holdFirst = 2;
    s.holdLast = 3;
    EXPECT_EQ(util::retimeSchedule(s), (Frames{5, 5, 5, 6, 7, 7, 7, 7}));
    EXPECT_EQ(util::retimedFrameCount(s), 8);
}

TEST(RetimeSchedule, UnusableSpecsAreRefusedBeforeAnythingIsBuilt)
{
    EXPECT_NE(util::retimeProblem(spec(5, 4, 1.0, 1.0)), "");
    EXPECT_NE(util::retimeProblem(spec(0, 4, 0.0, 1.0)), "");
    EXPECT_NE(util::retimeProblem(spec(0, 4, 1.0, -1.0)), "");
    EXPECT_NE(util::retimeProblem(spec(0, 4, 1.0, NAN)), "");
    // A billion frames: refused by the count, never allocated.
    EXPECT_NE(util::retimeProblem(spec(0, 1000, 1.0, 1e6)), "");
    EXPECT_EQ(util::retimedFrameCount(spec(0, 1000, 1.0, 1e6)), -1);
    EXPECT_THROW(util::retimeSchedule(spec(0, 1000, 1.0, 1e6)), std::invalid_argument);
}

namespace {

class RetimeNodeTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        registerCoreDataTypes(registry);
        registerNodeDataTypes(registry);
        registerFixtureNodes(registry);
        registerRetimeNode(registry);
        // The "written" sequence: frame f's file holds "f".
        fs::create_directories(out / "src");
        for (int f = 0; f <= 10; ++f)
            std::ofstream(util::framePath(out / "src/f.####.txt", f)) << f;
    }

    Graph parse(const std::string& params, const std::string& file = "shot/r.####.txt")
    {
        return parseGraph(R"({"cloudgraph": 1, "frames": {"start": 0, "end": 10},
            "timeStep": 2.0, "nodes": {
            "text": {"type": "TestTextSource"},
            "retime": {"type": "Retime", "inputs": {"frames": "text.value"},
                       "params": {"source": "src/f.####.txt", "file": ")" +
                              file + "\", " + params + "}}}}",
                          "test.json", registry);
    }

    void run(const Graph& g)
    {
        EvaluatorOptions options;
        options.outDir = out.path();
        Evaluator(registry, options).cookFrames(g, 0, 10);
    }

    std::string read(int number) const
    {
        std::ifstream in(util::framePath(out / "shot/r.####.txt", number));
        return std::string(std::istreambuf_iterator<char>(in), {});
    }

    std::size_t written() const
    {
        if (!fs::exists(out / "shot")) return 0;
        std::size_t n = 0;
        for (const auto& e : fs::directory_iterator(out / "shot")) n += e.is_regular_file();
        return n;
    }

    Registry registry;
    test::TempDir out;
};

}  // namespace

TEST_F(RetimeNodeTest, WritesTheFramesItPromisesNumberedFromTheChosenFirst)
{
    // A time-lapse of frames 2..10 at every second frame, held 2 frames at each end, from 1001.
    run(parse(R"("firstFrame": 2, "framesPerSecond": 0.25, "holdFirst": 2, "holdLast": 2,
                 "numberFrom": 1001)"));
    const std::vector<std::string> expected = {"2", "2", "2", "4", "6", "8", "10", "10", "10"};
    ASSERT_EQ(written(), expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k)
        EXPECT_EQ(read(1001 + static_cast<int>(k)), expected[k]) << k;
    // Run again: the same files, and nothing left beside them.
    run(parse(R"("firstFrame": 2, "framesPerSecond": 0.25, "holdFirst": 2, "holdLast": 2,
                 "numberFrom": 1001)"));
    EXPECT_EQ(written(), expected.size());
    EXPECT_EQ(read(1005), "6");
}

TEST_F(RetimeNodeTest, AMissingSourceIsNamedAndNothingIsWritten)
{
    fs::remove(util::framePath(out / "src/f.####.txt", 7));
    try {
        run(parse(R"("numberFrom": 1)"));
        FAIL() << "a missing frame was not noticed";
    } catch (const CookError& e) {
        EXPECT_TRUE(e.inputFault());
        EXPECT_NE(std::string(e.what()).find("f.0007.txt"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("retime"), std::string::npos) << e.what();
    }
    EXPECT_EQ(written(), 0u);
    EXPECT_FALSE(fs::exists(out / "shot"));  // not even its folder
}

TEST_F(RetimeNodeTest, PatternsWithoutAFrameNumberOrOverwritingTheSourceAreRefused)
{
    EXPECT_NO_THROW(parse(R"("numberFrom": 1)"));
    EXPECT_THROW(parse(R"("numberFrom": 1)", "shot/r.txt"), InputError);
    EXPECT_THROW(parse(R"("numberFrom": 1)", "src/f.####.txt"), InputError);
    // Another name for the same files: caught when it would write.
    try {
        run(parse(R"("holdLast": 1)", "src/./f.####.txt"));
        ADD_FAILURE() << "the retime overwrote its source";
    } catch (const CookError& e) {
        EXPECT_NE(std::string(e.what()).find("would overwrite"), std::string::npos) << e.what();
    }
    for (int f = 0; f <= 10; ++f) {
        std::ifstream in(util::framePath(out / "src/f.####.txt", f));
        EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), std::to_string(f));
    }
}

}  // namespace cg
