#include "nodes/atmosphere/SoundingProfile.h"

#include <cmath>
#include <vector>

namespace cg {

algo::EnvironmentProfile profileFromSounding(const formats::Sounding& sounding)
{
    constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180.0;
    std::vector<algo::ProfileLevel> levels;
    levels.reserve(sounding.levels.size());
    for (const formats::SoundingLevel& s : sounding.levels) {
        algo::ProfileLevel l;
        l.heightM = s.heightM;
        l.temperatureC = s.temperatureC;
        l.dewpointC = s.dewpointC;
        l.pressureHPa = s.pressureHPa;
        const double from = s.windFromDeg * kRadiansPerDegree;
        l.windEastMs = -s.windSpeedMs * std::sin(from);  // NaN stays NaN: a missing wind
        l.windNorthMs = -s.windSpeedMs * std::cos(from);
        levels.push_back(l);
    }
    return algo::EnvironmentProfile(std::move(levels));
}

}  // namespace cg
