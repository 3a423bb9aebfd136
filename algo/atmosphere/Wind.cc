#include "algo/atmosphere/Wind.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace cg::algo {

WindProfile::WindProfile(std::vector<WindLevel> levels) : mLevels(std::move(levels))
{
    for (std::size_t i = 0; i < mLevels.size(); ++i) {
        const WindLevel& l = mLevels[i];
        if (!std::isfinite(l.heightM) || !std::isfinite(l.east) || !std::isfinite(l.north))
            throw std::invalid_argument("wind level " + std::to_string(i) + " is not finite");
        if (i > 0 && !(l.heightM > mLevels[i - 1].heightM))
            throw std::invalid_argument("wind heights must increase (level " + std::to_string(i) +
                                        ")");
    }
}

Wind windFromDirection(double speed, double fromDegrees)
{
    constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180.0;
    const double from = fromDegrees * kRadiansPerDegree;
    return {-speed * std::sin(from), -speed * std::cos(from)};
}

WindProfile WindProfile::fromSpeedAndDirection(const std::vector<double>& heightsM,
                                               const std::vector<double>& speedsMs,
                                               const std::vector<double>& fromDegrees)
{
    if (speedsMs.size() != heightsM.size() || fromDegrees.size() != heightsM.size())
        throw std::invalid_argument("wind heights, speeds and directions differ in number (" +
                                    std::to_string(heightsM.size()) + ", " +
                                    std::to_string(speedsMs.size()) + ", " +
                                    std::to_string(fromDegrees.size()) + ")");
    std::vector<WindLevel> levels;
    for (std::size_t i = 0; i < heightsM.size(); ++i) {
        const Wind w = windFromDirection(speedsMs[i], fromDegrees[i]);
        levels.push_back({heightsM[i], w.east, w.north});
    }
    return WindProfile(std::move(levels));
}

Wind WindProfile::at(double heightM) const
{
    if (mLevels.empty()) return {};
    if (heightM <= mLevels.front().heightM) return {mLevels.front().east, mLevels.front().north};
    if (heightM >= mLevels.back().heightM) return {mLevels.back().east, mLevels.back().north};
    const auto above =
        std::upper_bound(mLevels.begin(), mLevels.end(), heightM,
                         [](double value, const WindLevel& l) { return value < l.heightM; });
    const WindLevel& hi = *above;
    const WindLevel& lo = *(above - 1);
    const double w = (heightM - lo.heightM) / (hi.heightM - lo.heightM);
    return {(1.0 - w) * lo.east + w * hi.east, (1.0 - w) * lo.north + w * hi.north};
}

Wind WindProfile::meanBelow(double topM) const
{
    if (mLevels.empty() || !(topM > 0.0)) return {};
    // Trapezoids between the level heights inside [0, topM] are exact for a linear profile.
    std::vector<double> heights{0.0};
    for (const WindLevel& l : mLevels)
        if (l.heightM > 0.0 && l.heightM < topM) heights.push_back(l.heightM);
    heights.push_back(topM);
    Wind sum;
    for (std::size_t i = 1; i < heights.size(); ++i) {
        const Wind a = at(heights[i - 1]), b = at(heights[i]);
        const double dz = heights[i] - heights[i - 1];
        sum.east += 0.5 * (a.east + b.east) * dz;
        sum.north += 0.5 * (a.north + b.north) * dz;
    }
    return {sum.east / topM, sum.north / topM};
}

WindProfile WindProfile::relativeTo(Wind motion) const
{
    std::vector<WindLevel> levels = mLevels;
    for (WindLevel& l : levels) {
        l.east -= motion.east;
        l.north -= motion.north;
    }
    return WindProfile(std::move(levels));
}

}  // namespace cg::algo
