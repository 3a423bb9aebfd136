#include "nodes/atmosphere/SoundingProfile.h"

#include "algo/atmosphere/Wind.h"

#include <vector>

namespace cg {

algo::EnvironmentProfile profileFromSounding(const formats::Sounding& sounding)
{
    std::vector<algo::ProfileLevel> levels;
    levels.reserve(sounding.levels.size());
    for (const formats::SoundingLevel& s : sounding.levels) {
        algo::ProfileLevel l;
        l.heightM = s.heightM;
        l.temperatureC = s.temperatureC;
        l.dewpointC = s.dewpointC;
        l.pressureHPa = s.pressureHPa;
        const algo::Wind w = algo::windFromDirection(s.windSpeedMs, s.windFromDeg);
        l.windEastMs = w.east;  // NaN stays NaN: a missing wind
        l.windNorthMs = w.north;
        levels.push_back(l);
    }
    return algo::EnvironmentProfile(std::move(levels));
}

}  // namespace cg
