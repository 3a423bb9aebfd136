// Issue 15's growth: on the small version of every figure graph, the cloud keeps developing to
// the end of its frame range. From the tenth in which the cloud appears up to 90% of the
// range, its particle count and its top both increase in every tenth.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Registry.h"
#include "golden/GoldenRun.h"
#include "golden/GoldenSpecs.h"
#include "nodes/Builtin.h"
#include "nodes/data/CloudParticles.h"

namespace cg::golden {

namespace {

struct CloudSize {
    std::size_t count = 0;
    float top = 0.0f;  ///< highest cloud particle, metres
};

/// The cloud at the start of each tenth of the graph's range and at its last frame (11 values).
std::vector<CloudSize> cloudByTenth(const std::string& name)
{
    Registry registry;
    registerBuiltinNodes(registry);
    Graph g = loadGraph(graphsDir() / (name + ".json"), registry);
    findSpec(name)->shrink(g);
    const int first = g.frames.start, last = g.frames.end;
    std::vector<int> marks;
    for (int k = 0; k <= 10; ++k) marks.push_back(first + (last - first) * k / 10);
    std::vector<CloudSize> sizes;
    Evaluator ev(registry, {});
    ev.cookFrames(g, first, last, {"cloud"}, [&](int frame, const Evaluator::FrameOutputs& r) {
        if (std::find(marks.begin(), marks.end(), frame) == marks.end()) return;
        const auto cloud = std::dynamic_pointer_cast<const CloudParticlesData>(
            r[g.indexOf("cloud")]->at("particles"));
        CloudSize s;
        s.count = cloud->size();
        for (std::size_t i = 0; i < s.count; ++i)
            s.top = std::max(s.top, cloud->positions()[3 * i + 2]);
        sizes.push_back(s);
    });
    return sizes;
}

class FigureGrowth : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(FigureGrowth, CountAndTopIncreaseInEveryTenthUpTo90Percent)
{
    const std::vector<CloudSize> at = cloudByTenth(GetParam());
    ASSERT_EQ(at.size(), 11u);
    std::size_t k = 0;
    while (k < 10 && at[k + 1].count == 0) ++k;  // tenths before the cloud appears
    ASSERT_LT(k, 9u) << "the cloud appears in the last tenth";
    for (; k < 9; ++k) {
        char text[160];
        std::snprintf(text, sizeof text, "tenth %zu: %zu -> %zu particles, top %.0f -> %.0f m",
                      k + 1, at[k].count, at[k + 1].count, at[k].top, at[k + 1].top);
        EXPECT_GT(at[k + 1].count, at[k].count) << text;
        EXPECT_GT(at[k + 1].top, at[k].top) << text;
        std::printf("%s %s\n", GetParam().c_str(), text);
    }
}

INSTANTIATE_TEST_SUITE_P(Figures, FigureGrowth,
                         ::testing::Values("figure1_cloudscape", "figure5_progress",
                                           "figure6_towering_cumulus", "figure7a_beta33",
                                           "figure7b_beta27", "figure8_cumulonimbus",
                                           "figure8_cumulonimbus_sounding", "figure9_sparse"),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

}  // namespace cg::golden
