// FramePipeline: each node cooks its frames in order (unless it is of any order) and after its
// inputs, frames finish in order, the next frame's first nodes overlap the last nodes of the
// frame before, and a failure stops the frames from its own on while the earlier ones finish.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <tbb/task_arena.h>

#include "core/CoreData.h"
#include "core/FramePipeline.h"

namespace cg {
namespace {

// A chain source (0) -> middle (1) -> sink (2), and a side node (3) reading the source.
const std::vector<std::vector<std::size_t>> kUpstream = {{}, {0}, {1}, {0}};

OutputsPtr outputOf(std::size_t node, int frame)
{
    auto out = std::make_shared<OutputMap>();
    (*out)["v"] = std::make_shared<TextData>(std::to_string(node) + "@" + std::to_string(frame));
    return out;
}

std::vector<std::size_t> allNodes(int, FramePipeline::FrameOutputs&) { return {0, 1, 2, 3}; }

/// Waits (at most 20 s) until `flag` is set, then a little more: long enough for the
/// pipeline to take in a failure thrown just after the flag was set.
void waitFor(const std::atomic<bool>& flag)
{
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!flag && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
}

/// The cooks in the order they finished.
struct Log {
    std::mutex mutex;
    std::vector<std::pair<std::size_t, int>> cooked;
    void add(std::size_t node, int frame)
    {
        std::lock_guard<std::mutex> lock(mutex);
        cooked.emplace_back(node, frame);
    }
    std::size_t position(std::size_t node, int frame)
    {
        for (std::size_t i = 0; i < cooked.size(); ++i)
            if (cooked[i] == std::make_pair(node, frame)) return i;
        return cooked.size();
    }
};

TEST(FramePipeline, NodesCookInFrameOrderAfterTheirInputsAndFramesFinishInOrder)
{
    Log log;
    std::vector<int> finished;
    FramePipeline(kUpstream, 2)
        .run(
            0, 9, allNodes,
            [&](std::size_t node, int frame, const FramePipeline::FrameOutputs& results) {
                for (std::size_t up : kUpstream[node]) {
                    EXPECT_TRUE(results[up]) << node << "@" << frame << " before its input";
                    const auto& text = static_cast<const TextData&>(*results[up]->at("v"));
                    EXPECT_EQ(text.value, std::to_string(up) + "@" + std::to_string(frame));
                }
                log.add(node, frame);
                return outputOf(node, frame);
            },
            [&](int frame, const FramePipeline::FrameOutputs& results) {
                for (std::size_t node = 0; node < 4; ++node) EXPECT_TRUE(results[node]);
                finished.push_back(frame);
            });
    ASSERT_EQ(log.cooked.size(), 40u);
    for (std::size_t node = 0; node < 4; ++node)
        for (int frame = 1; frame < 10; ++frame)
            EXPECT_LT(log.position(node, frame - 1), log.position(node, frame)) << node;
    EXPECT_EQ(finished, (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
}

TEST(FramePipeline, TheNextFramesSourceCooksWhileThisFramesSinkDoes)
{
    // The sink at frame 0 waits (at most 20 s) for the source at frame 1: with one frame at a
    // time it would never come.
    tbb::task_arena arena(2);
    std::atomic<bool> nextSourceStarted{false};
    bool overlapped = false;
    arena.execute([&] {
        FramePipeline(kUpstream, 2)
            .run(
                0, 1, allNodes,
                [&](std::size_t node, int frame, const FramePipeline::FrameOutputs&) {
                    if (node == 0 && frame == 1) nextSourceStarted = true;
                    if (node == 2 && frame == 0) {
                        waitFor(nextSourceStarted);
                        overlapped = nextSourceStarted;
                    }
                    return outputOf(node, frame);
                },
                [](int, const FramePipeline::FrameOutputs&) {});
    });
    EXPECT_TRUE(overlapped);
}

TEST(FramePipeline, ANodeOfAnyOrderCooksTheNextFrameWhileThisOneCooksAndTheOthersKeepOrder)
{
    // The middle node, of any order, waits at frame 0 (at most 20 s) for itself at frame 1:
    // in frame order it would never come. The sink still cooks its frames in order.
    tbb::task_arena arena(2);
    std::atomic<bool> nextMiddleStarted{false};
    bool overlapped = false;
    Log log;
    std::vector<int> finished;
    arena.execute([&] {
        FramePipeline(kUpstream, 2, {false, true, false, false})
            .run(
                0, 3, allNodes,
                [&](std::size_t node, int frame, const FramePipeline::FrameOutputs& results) {
                    for (std::size_t up : kUpstream[node])
                        EXPECT_TRUE(results[up]) << node << "@" << frame << " before its input";
                    if (node == 1 && frame == 1) nextMiddleStarted = true;
                    if (node == 1 && frame == 0) {
                        waitFor(nextMiddleStarted);
                        overlapped = nextMiddleStarted;
                    }
                    log.add(node, frame);
                    return outputOf(node, frame);
                },
                [&](int frame, const FramePipeline::FrameOutputs&) { finished.push_back(frame); });
    });
    EXPECT_TRUE(overlapped);
    EXPECT_LT(log.position(1, 1), log.position(1, 0));
    for (int frame = 1; frame < 4; ++frame)
        EXPECT_LT(log.position(2, frame - 1), log.position(2, frame));
    EXPECT_EQ(finished, (std::vector<int>{0, 1, 2, 3}));
}

TEST(FramePipeline, AFailureStopsItsFrameAndLaterOnesWhileEarlierFramesFinish)
{
    Log log;
    std::vector<int> finished;
    std::atomic<bool> threw{false};
    try {
        FramePipeline(kUpstream, 2)
            .run(
                0, 9, allNodes,
                [&](std::size_t node, int frame, const FramePipeline::FrameOutputs&) {
                    // The middle node fails at frame 3 while the sink at frame 2 is cooking.
                    if (node == 1 && frame == 3) {
                        threw = true;
                        throw std::runtime_error("middle@3");
                    }
                    if (node == 2 && frame == 2) waitFor(threw);
                    log.add(node, frame);
                    return outputOf(node, frame);
                },
                [&](int frame, const FramePipeline::FrameOutputs&) { finished.push_back(frame); });
        FAIL() << "expected the failure to be rethrown";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "middle@3");
    }
    EXPECT_EQ(finished, (std::vector<int>{0, 1, 2}));
    EXPECT_LT(log.position(2, 2), log.cooked.size());  // frame 2's sink finished
    for (int frame = 3; frame < 10; ++frame) {
        EXPECT_EQ(log.position(1, frame), log.cooked.size());
        EXPECT_EQ(log.position(2, frame), log.cooked.size());
    }
    for (int frame = 4; frame < 10; ++frame) EXPECT_EQ(log.position(0, frame), log.cooked.size());
}

TEST(FramePipeline, TheEarliestFramesFailureIsTheOneRethrown)
{
    std::atomic<bool> threw{false};
    try {
        FramePipeline(kUpstream, 2)
            .run(
                0, 5, allNodes,
                [&](std::size_t node, int frame, const FramePipeline::FrameOutputs&) {
                    // Frame 2's side node fails after frame 3's source has failed.
                    if (node == 0 && frame == 3) {
                        threw = true;
                        throw std::runtime_error("source@3");
                    }
                    if (node == 3 && frame == 2) {
                        waitFor(threw);
                        throw std::runtime_error("side@2");
                    }
                    return outputOf(node, frame);
                },
                [](int, const FramePipeline::FrameOutputs&) {});
        FAIL() << "expected a failure";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "side@2");
    }
}

TEST(FramePipeline, PlannedNodesAloneCookAndSettledResultsReachTheirReaders)
{
    // At odd frames the plan settles the middle node itself (as a verified writer's record
    // is): only the sink reads it, and the middle node does not cook.
    Log log;
    FramePipeline(kUpstream, 2)
        .run(
            0, 5,
            [](int frame, FramePipeline::FrameOutputs& results) {
                if (frame % 2 == 0) return std::vector<std::size_t>{0, 1, 2, 3};
                results[1] = outputOf(1, frame);
                return std::vector<std::size_t>{0, 2, 3};
            },
            [&](std::size_t node, int frame, const FramePipeline::FrameOutputs& results) {
                if (node == 2) {
                    EXPECT_TRUE(results[1]);
                }
                log.add(node, frame);
                return outputOf(node, frame);
            },
            [](int, const FramePipeline::FrameOutputs&) {});
    EXPECT_EQ(log.cooked.size(), 21u);
    for (int frame = 1; frame < 6; frame += 2) EXPECT_EQ(log.position(1, frame), log.cooked.size());
}

}  // namespace
}  // namespace cg
