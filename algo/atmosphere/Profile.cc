#include "algo/atmosphere/Profile.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "algo/atmosphere/Thermodynamics.h"

namespace cg::algo {

namespace {

constexpr double kSeaLevelPressure = 1013.25;  // hPa, ICAO
constexpr double kStandardLapse = 6.5e-3;      // C per metre, ICAO troposphere

/// Fills the missing (NaN) values of one member by linear interpolation in height between
/// the levels that have it; beyond the last one, `extend` gives the value from that level.
template <typename Member, typename Extend>
void fillByInterpolation(std::vector<ProfileLevel>& levels, Member member, Extend extend)
{
    std::size_t previous = levels.size();  // the last level with a value, none yet
    for (std::size_t i = 0; i < levels.size(); ++i) {
        if (std::isnan(levels[i].*member)) continue;
        if (previous < levels.size())
            for (std::size_t k = previous + 1; k < i; ++k) {
                const double w = (levels[k].heightM - levels[previous].heightM) /
                                 (levels[i].heightM - levels[previous].heightM);
                levels[k].*member = (1.0 - w) * levels[previous].*member + w * levels[i].*member;
            }
        previous = i;
    }
    for (std::size_t k = previous + 1; k < levels.size(); ++k)
        levels[k].*member = extend(levels[previous], levels[k]);
}

void fillPressures(std::vector<ProfileLevel>& levels)
{
    std::size_t first = levels.size();
    for (std::size_t i = 0; i < levels.size() && first == levels.size(); ++i)
        if (!std::isnan(levels[i].pressureHPa)) first = i;
    if (first == levels.size()) {  // none given: hydrostatic from sea level
        const ProfileLevel& g = levels.front();
        levels.front().pressureHPa = thermo::hydrostaticPressure(
            kSeaLevelPressure, g.temperatureC + kStandardLapse * g.heightM, g.temperatureC,
            g.heightM);
        first = 0;
    }
    for (std::size_t k = first; k-- > 0;)  // downward from the first given
        levels[k].pressureHPa = thermo::hydrostaticPressure(
            levels[k + 1].pressureHPa, levels[k + 1].temperatureC, levels[k].temperatureC,
            levels[k].heightM - levels[k + 1].heightM);
    for (std::size_t k = first + 1; k < levels.size(); ++k)
        if (std::isnan(levels[k].pressureHPa))
            levels[k].pressureHPa = thermo::hydrostaticPressure(
                levels[k - 1].pressureHPa, levels[k - 1].temperatureC, levels[k].temperatureC,
                levels[k].heightM - levels[k - 1].heightM);
}

}  // namespace

EnvironmentProfile::EnvironmentProfile(std::vector<ProfileLevel> levels)
    : mLevels(std::move(levels))
{
    if (mLevels.size() < 2) throw std::invalid_argument("a profile needs at least two levels");
    for (std::size_t i = 0; i < mLevels.size(); ++i) {
        const ProfileLevel& l = mLevels[i];
        if (!std::isfinite(l.heightM) || !std::isfinite(l.temperatureC))
            throw std::invalid_argument("profile level " + std::to_string(i) +
                                        " has no height or temperature");
        if (i > 0 && !(l.heightM > mLevels[i - 1].heightM))
            throw std::invalid_argument("profile heights must increase (level " +
                                        std::to_string(i) + ")");
    }
    if (std::isnan(mLevels.front().dewpointC))
        throw std::invalid_argument("the first profile level needs a dew point");

    fillByInterpolation(mLevels, &ProfileLevel::dewpointC,
                        [](const ProfileLevel& last, const ProfileLevel& l) {
                            return l.temperatureC - (last.temperatureC - last.dewpointC);
                        });
    bool anyWind = false;
    mWindTop = -std::numeric_limits<double>::infinity();
    for (const ProfileLevel& l : mLevels)
        if (!std::isnan(l.windEastMs) && !std::isnan(l.windNorthMs)) {
            anyWind = true;
            mWindTop = l.heightM;
        }
    for (ProfileLevel& l : mLevels)
        if (!anyWind || std::isnan(l.windEastMs) || std::isnan(l.windNorthMs))
            l.windEastMs = l.windNorthMs = anyWind ? std::nan("") : 0.0;
    if (anyWind) {
        const auto keep = [](double ProfileLevel::*m) {
            return [m](const ProfileLevel& last, const ProfileLevel&) { return last.*m; };
        };
        fillByInterpolation(mLevels, &ProfileLevel::windEastMs, keep(&ProfileLevel::windEastMs));
        fillByInterpolation(mLevels, &ProfileLevel::windNorthMs, keep(&ProfileLevel::windNorthMs));
        // Levels below the first with wind take its wind.
        for (std::size_t i = mLevels.size(); i-- > 1;)
            if (std::isnan(mLevels[i - 1].windEastMs)) {
                mLevels[i - 1].windEastMs = mLevels[i].windEastMs;
                mLevels[i - 1].windNorthMs = mLevels[i].windNorthMs;
            }
    }
    fillPressures(mLevels);
}

EnvironmentProfile::EnvironmentProfile(std::vector<ProfileLevel> levels, double windTopHeight)
    : EnvironmentProfile(std::move(levels))
{
    const bool atALevel = std::any_of(mLevels.begin(), mLevels.end(), [&](const ProfileLevel& l) {
        return l.heightM == windTopHeight;
    });
    if (!(windTopHeight == -std::numeric_limits<double>::infinity() || atALevel))
        throw std::invalid_argument("the wind's top is not one of the profile's levels");
    mWindTop = windTopHeight;
}

std::size_t EnvironmentProfile::segment(double z, double& weight) const
{
    const auto above =
        std::upper_bound(mLevels.begin(), mLevels.end(), z,
                         [](double value, const ProfileLevel& l) { return value < l.heightM; });
    if (above == mLevels.begin()) {
        weight = 0.0;
        return 0;
    }
    if (above == mLevels.end()) {
        weight = 1.0;
        return mLevels.size() - 2;
    }
    const auto i = static_cast<std::size_t>(above - mLevels.begin()) - 1;
    weight = (z - mLevels[i].heightM) / (mLevels[i + 1].heightM - mLevels[i].heightM);
    return i;
}

double EnvironmentProfile::temperature(double z) const
{
    double w = 0.0;
    const std::size_t i = segment(z, w);
    return (1.0 - w) * mLevels[i].temperatureC + w * mLevels[i + 1].temperatureC;
}

double EnvironmentProfile::dewpoint(double z) const
{
    double w = 0.0;
    const std::size_t i = segment(z, w);
    return (1.0 - w) * mLevels[i].dewpointC + w * mLevels[i + 1].dewpointC;
}

double EnvironmentProfile::pressure(double z) const
{
    double w = 0.0;
    const std::size_t i = segment(z, w);
    return std::exp((1.0 - w) * std::log(mLevels[i].pressureHPa) +
                    w * std::log(mLevels[i + 1].pressureHPa));
}

Wind EnvironmentProfile::wind(double z) const
{
    double w = 0.0;
    const std::size_t i = segment(z, w);
    return {(1.0 - w) * mLevels[i].windEastMs + w * mLevels[i + 1].windEastMs,
            (1.0 - w) * mLevels[i].windNorthMs + w * mLevels[i + 1].windNorthMs};
}

EnvironmentProfile standardAtmosphere(double surfaceTemperatureC, double surfaceDewpointC,
                                      double tropopauseM, double topM, double spacingM)
{
    if (!(spacingM > 0.0) || !(tropopauseM > 0.0) || !(topM > tropopauseM) ||
        !(surfaceDewpointC <= surfaceTemperatureC))
        throw std::invalid_argument("standardAtmosphere: bad settings");
    const double depression = surfaceTemperatureC - surfaceDewpointC;
    const auto temperatureAt = [&](double z) {
        return surfaceTemperatureC - kStandardLapse * std::min(z, tropopauseM);
    };
    std::vector<double> heights;
    for (double z = 0.0; z < topM; z += spacingM) heights.push_back(z);
    heights.push_back(topM);
    heights.push_back(tropopauseM);
    std::sort(heights.begin(), heights.end());
    heights.erase(std::unique(heights.begin(), heights.end()), heights.end());

    std::vector<ProfileLevel> levels;
    for (double z : heights) {
        ProfileLevel l;
        l.heightM = z;
        l.temperatureC = temperatureAt(z);
        l.dewpointC = l.temperatureC - depression;
        l.pressureHPa = levels.empty() ? kSeaLevelPressure
                                       : thermo::hydrostaticPressure(
                                             levels.back().pressureHPa, levels.back().temperatureC,
                                             l.temperatureC, z - levels.back().heightM);
        levels.push_back(l);
    }
    return EnvironmentProfile(std::move(levels));
}

}  // namespace cg::algo
