// A storm that lives (issue 54), on the reduced cumulonimbus_life of the golden harness: fed
// for its first half hour, it grows to its mature size, then its clouds evaporate: by the end
// of the hour the tower is gone and a third of its anvil is left. Counts of cloud particles: a
// golden statistic on a reduced graph, not a timed test.

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

TEST(StormLife, SmallCumulonimbusGrowsForHalfAnHourThenItsTowerEvaporatesBeforeItsAnvil)
{
    Registry registry;
    registerBuiltinNodes(registry);
    Graph g = loadGraph(graphsDir() / "cumulonimbus_life.json", registry);
    findSpec("cumulonimbus_life")->shrink(g);
    Evaluator ev(registry, {});
    // Cloud particles under and over 9 km: the anvil's copies are those from the graph's
    // anvilBase, 10 km, up, and their particles reach a kilometre under their origins.
    std::map<int, std::size_t> tower, anvil;
    for (const int f : {150, 300, 450, 600}) {
        const auto cloud = std::dynamic_pointer_cast<const CloudParticlesData>(
            ev.pull(g, "cloud", f)->at("particles"));
        ASSERT_TRUE(cloud);
        const auto& xyz = cloud->positions();
        for (std::size_t i = 0; i < cloud->size(); ++i)
            ++(xyz[3 * i + 2] < 9000.0f ? tower : anvil)[f];
    }
    std::printf(
        "small cumulonimbus_life: tower %zu, %zu, %zu and %zu, anvil %zu, %zu, %zu and %zu "
        "cloud particles at 15, 30, 45 and 60 minutes\n",
        tower[150], tower[300], tower[450], tower[600], anvil[150], anvil[300], anvil[450],
        anvil[600]);
    // Fed until 30 minutes (emissionDuration), the storm still grows then; 15 minutes (hold)
    // after its copies stop growing they evaporate, over up to 25 (decayTime), the anvil's
    // four times slower (anvilLife).
    EXPECT_GT(tower[300] + anvil[300], tower[150] + anvil[150]);
    EXPECT_LT(tower[450], tower[300] / 2);
    EXPECT_LT(tower[600], tower[300] / 50);
    EXPECT_GT(anvil[600], anvil[300] / 5) << "the anvil outlives the tower";
    EXPECT_GT(anvil[600], 10 * tower[600]);
}

}  // namespace cg::golden
