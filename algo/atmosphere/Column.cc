#include "algo/atmosphere/Column.h"

#include <algorithm>
#include <cmath>

namespace cg::algo {

EnvironmentColumn sampleColumn(const EnvironmentProfile* profile, const WindProfile& wind)
{
    const double ground = profile ? profile->groundHeight() : 0.0;
    double depth = profile ? profile->topHeight() - ground : 0.0;
    if (!wind.calm()) depth = std::max(depth, wind.levels().back().heightM);
    EnvironmentColumn c;
    c.step = std::max(10.0, depth / static_cast<double>(kMaxColumnSamples - 2));
    const auto samples = static_cast<std::size_t>(std::ceil(depth / c.step)) + 2;
    for (std::size_t k = 0; k < samples; ++k) {
        const double z = static_cast<double>(k) * c.step;
        if (profile) {
            c.temperature.push_back(static_cast<float>(profile->temperature(ground + z)));
            c.dewpoint.push_back(static_cast<float>(profile->dewpoint(ground + z)));
            c.pressure.push_back(static_cast<float>(profile->pressure(ground + z)));
        }
        if (!wind.calm()) {
            const Wind w = wind.at(z);
            c.windEast.push_back(static_cast<float>(w.east));
            c.windNorth.push_back(static_cast<float>(w.north));
        }
    }
    return c;
}

}  // namespace cg::algo
