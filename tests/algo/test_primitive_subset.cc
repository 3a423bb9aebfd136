// everyKthParticle: ids 0, k, 2k, ... of each frame, so frame s keeps ceil(N_f(s) / k) and
// every kept particle keeps its own trajectory.

#include <gtest/gtest.h>

#include <vector>

#include "algo/mapping/PrimitiveSubset.h"

namespace cg {

TEST(PrimitiveSubset, KeepsEveryKthIdOnItsTrajectory)
{
    // Frame s holds ids 0..N_f(s)-1; particle id's position is (id, s, 0).
    const std::vector<std::uint32_t> counts = {1, 4, 7};
    std::vector<float> positions;
    for (std::size_t s = 0; s < counts.size(); ++s)
        for (std::uint32_t id = 0; id < counts[s]; ++id)
            positions.insert(positions.end(), {float(id), float(s), 0.0f});

    std::vector<std::uint32_t> keptCounts;
    std::vector<float> kept;
    algo::everyKthParticle(counts, positions, 3, keptCounts, kept);
    EXPECT_EQ(keptCounts, (std::vector<std::uint32_t>{1, 2, 3}));  // ceil(N_f / 3)
    const std::vector<float> expected = {0, 0, 0, 0, 1, 0, 3, 1, 0, 0, 2, 0, 3, 2, 0, 6, 2, 0};
    EXPECT_EQ(kept, expected);

    EXPECT_EQ(algo::subsetStride(7, 3), 3u);
    EXPECT_EQ(algo::subsetStride(6, 3), 2u);
    EXPECT_EQ(algo::subsetStride(2, 16384), 1u);
    EXPECT_EQ(algo::subsetStride(0, 5), 1u);
}

}  // namespace cg
