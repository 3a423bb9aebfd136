#include "algo/render/image/CloudLayer.h"

#include <algorithm>
#include <cstddef>
#include <stdexcept>

namespace cg::algo {

std::vector<float> cloudLayer(const std::vector<float>& rgba, const std::vector<float>& background)
{
    if (rgba.size() % 4 != 0 || background.size() / 3 != rgba.size() / 4 ||
        background.size() % 3 != 0)
        throw std::invalid_argument("cloudLayer: the beauty and the background differ in size");
    const std::size_t n = rgba.size() / 4;
    std::vector<float> cloud(rgba.size(), 0.0f);
    for (std::size_t i = 0; i < n; ++i) {
        const float* beauty = &rgba[4 * i];
        const float alpha = beauty[3];
        if (alpha == 0.0f) continue;
        const double behind = 1.0 - static_cast<double>(alpha);
        for (int c = 0; c < 3; ++c)
            cloud[4 * i + c] = static_cast<float>(
                std::max(0.0, static_cast<double>(beauty[c]) -
                                  behind * static_cast<double>(background[3 * i + c])));
        cloud[4 * i + 3] = alpha;
    }
    return cloud;
}

}  // namespace cg::algo
