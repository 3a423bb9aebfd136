// A storm that lives (issue 54), on the reduced cumulonimbus_life of the golden harness: fed
// for its first half hour, it grows to its mature size, then its clouds evaporate and by the
// end of the hour it is gone. Counts of cloud particles: a golden statistic on a reduced
// graph, not a timed test.

#include <gtest/gtest.h>

#include <cstdio>
#include <map>

#include "core/Evaluator.h"
#include "core/Graph.h"
#include "core/Registry.h"
#include "golden/GoldenRun.h"
#include "golden/GoldenSpecs.h"
#include "nodes/Builtin.h"
#include "nodes/data/CloudParticles.h"

namespace cg::golden {

TEST(StormLife, SmallCumulonimbusGrowsForHalfAnHourThenEvaporates)
{
    Registry registry;
    registerBuiltinNodes(registry);
    Graph g = loadGraph(graphsDir() / "cumulonimbus_life.json", registry);
    findSpec("cumulonimbus_life")->shrink(g);
    Evaluator ev(registry, {});
    std::map<int, std::size_t> particles;
    for (const int f : {150, 300, 450, 600}) {
        const auto cloud = std::dynamic_pointer_cast<const CloudParticlesData>(
            ev.pull(g, "cloud", f)->at("particles"));
        ASSERT_TRUE(cloud);
        particles[f] = cloud->size();
    }
    std::printf(
        "small cumulonimbus_life: %zu, %zu, %zu and %zu cloud particles at 15, 30, 45 "
        "and 60 minutes\n",
        particles[150], particles[300], particles[450], particles[600]);
    // Fed until 30 minutes (emissionDuration), the storm still grows then; 15 minutes (hold)
    // after its copies stop growing they evaporate, over up to 25 (decayTime).
    EXPECT_GT(particles[300], particles[150]);
    EXPECT_LT(particles[450], particles[300] / 2);
    EXPECT_LT(particles[600], particles[300] / 50);
}

}  // namespace cg::golden
