// Where serve's page opens (cli/LastCloudFrame.h): the last frame with cloud particles, found
// by sampling back from the end, and the node upstream of a preview that makes them.

#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "cli/LastCloudFrame.h"
#include "core/Registry.h"
#include "nodes/Builtin.h"

namespace cg::cli {

namespace {

/// A counter of the frames asked for, with cloud on [from, to].
struct Clouds {
    int from, to;
    std::set<int> asked;
    std::size_t operator()(int f)
    {
        asked.insert(f);
        return f >= from && f <= to ? 10 : 0;
    }
};

std::optional<int> search(Clouds& c, int start, int end, int stride)
{
    return lastFrameWithParticles([&](int f) { return c(f); }, start, end, stride);
}

}  // namespace

TEST(LastCloudFrame, FindsTheLastFrameWithParticlesExactlyBetweenSamples)
{
    // Clouds from 62 to 137 in 0..200, sampled every 12 back from 200: 200, 188, ..., 140
    // have none, 128 has; then 139 down to 129 are looked at one by one: 137.
    Clouds c{62, 137, {}};
    EXPECT_EQ(search(c, 0, 200, 12), 137);
    EXPECT_TRUE(c.asked.count(140) && c.asked.count(138) && c.asked.count(137));
    EXPECT_FALSE(c.asked.count(136)) << "nothing before the answer is cooked";
    // A cloud at the end: the end, after one sample.
    Clouds end{62, 200, {}};
    EXPECT_EQ(search(end, 0, 200, 12), 200);
    EXPECT_EQ(end.asked.size(), 1u);
    // Only at the start; stride 1 and a stride wider than the range.
    Clouds first{0, 0, {}};
    EXPECT_EQ(search(first, 0, 50, 1), 0);
    Clouds wide{3, 9, {}};
    EXPECT_EQ(search(wide, 0, 20, 100), std::nullopt) << "the one sample (20) has none";
    EXPECT_EQ(search(wide, 0, 20, 0), 9) << "a stride below 1 is 1";
    // None anywhere.
    Clouds none{500, 600, {}};
    EXPECT_EQ(search(none, 0, 200, 7), std::nullopt);
}

TEST(LastCloudFrame, TheCloudSourceIsTheNearestNodeUpstreamWithCloudParticles)
{
    Registry registry;
    registerBuiltinNodes(registry);
    const Graph g = loadGraph(
        std::filesystem::path(CLOUDGRAPH_SOURCE_DIR) / "graphs/figure6_towering_cumulus.json",
        registry);
    const auto fromRender = cloudSourceOf(g, "render");
    ASSERT_TRUE(fromRender);
    EXPECT_EQ(fromRender->first, "cloud");
    EXPECT_EQ(fromRender->second, "particles");
    EXPECT_EQ(cloudSourceOf(g, "cloud"), fromRender) << "the node itself counts";
    EXPECT_EQ(cloudSourceOf(g, "primitive"), std::nullopt) << "above the cloud: none";
    EXPECT_EQ(cloudSourceOf(g, "no such node"), std::nullopt);
}

}  // namespace cg::cli
