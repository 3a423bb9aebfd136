// The cloud layer: what remains of the beauty once the background seen through the cloud is
// taken away, premultiplied by the cloud's alpha.

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "algo/render/image/CloudLayer.h"

namespace cg {

TEST(CloudLayer, RemovesTheBackgroundSeenThroughTheCloud)
{
    // Clear sky; half-transparent cloud; opaque cloud; a beauty rounded just below
    // (1 - alpha) background (clamped at 0, not negative).
    const std::vector<float> rgba = {0.3f, 0.4f, 0.9f, 0.0f,  //
                                     0.7f, 0.8f, 1.0f, 0.5f,  //
                                     2.0f, 2.0f, 1.5f, 1.0f,  //
                                     0.2f, 0.2f, 0.2f, 0.5f};
    const std::vector<float> background = {0.3f,  0.4f, 0.9f,  //
                                           0.4f,  0.6f, 1.0f,  //
                                           0.3f,  0.4f, 0.9f,  //
                                           0.41f, 0.4f, 0.4f};
    const std::vector<float> cloud = algo::cloudLayer(rgba, background);
    const std::vector<float> expected = {0.0f, 0.0f, 0.0f, 0.0f,  //
                                         0.5f, 0.5f, 0.5f, 0.5f,  //
                                         2.0f, 2.0f, 1.5f, 1.0f,  //
                                         0.0f, 0.0f, 0.0f, 0.5f};
    ASSERT_EQ(cloud.size(), expected.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) EXPECT_FLOAT_EQ(cloud[i], expected[i]) << i;
}

TEST(CloudLayer, RefusesABackgroundOfAnotherSize)
{
    EXPECT_THROW(algo::cloudLayer(std::vector<float>(8), std::vector<float>(3)),
                 std::invalid_argument);
    EXPECT_THROW(algo::cloudLayer(std::vector<float>(8), std::vector<float>(8)),
                 std::invalid_argument);
    EXPECT_TRUE(algo::cloudLayer({}, {}).empty());
}

}  // namespace cg
