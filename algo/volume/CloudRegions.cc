#include "algo/volume/CloudRegions.h"

#include <utility>

namespace cg::algo {

Regions labelRegions(const Mask2D& m)
{
    Regions r;
    r.width = m.width;
    r.height = m.height;
    r.label.assign(m.set.size(), -1);
    const auto index = [&](int x, int y) {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(m.width) +
               static_cast<std::size_t>(x);
    };
    std::vector<std::pair<int, int>> stack;
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x) {
            if (!m.at(x, y) || r.label[index(x, y)] >= 0) continue;
            const auto id = static_cast<std::int32_t>(r.area.size());
            double area = 0, perimeter = 0;
            stack.assign(1, {x, y});
            r.label[index(x, y)] = id;
            while (!stack.empty()) {
                const auto [cx, cy] = stack.back();
                stack.pop_back();
                ++area;
                const int nx[4] = {cx + 1, cx - 1, cx, cx};
                const int ny[4] = {cy, cy, cy + 1, cy - 1};
                for (int k = 0; k < 4; ++k) {
                    if (!m.at(nx[k], ny[k])) {
                        ++perimeter;
                    } else if (r.label[index(nx[k], ny[k])] < 0) {
                        r.label[index(nx[k], ny[k])] = id;
                        stack.emplace_back(nx[k], ny[k]);
                    }
                }
            }
            r.area.push_back(area);
            r.perimeter.push_back(perimeter);
        }
    return r;
}

}  // namespace cg::algo
