#pragma once
/// The environment as a function of height: temperature, dew point, pressure and
/// wind from a sounding or the standard atmosphere, where the paper has Eq. 9's straight line.
/// Heights are above mean sea level in metres, temperatures in C, pressures in hPa, winds in
/// m/s toward the east and the north.

#include <cstddef>
#include <vector>

namespace cg::algo {

/// One level; NaN marks a value the source did not give (never height or temperature).
struct ProfileLevel {
    double heightM = 0.0;
    double temperatureC = 0.0;
    double dewpointC = 0.0;
    double pressureHPa = 0.0;
    double windEastMs = 0.0;
    double windNorthMs = 0.0;
};

struct Wind {
    double east = 0.0;
    double north = 0.0;
};

/// Values between levels are interpolated linearly in height (pressure log-linearly); below
/// the first level and above the last they are held at the end level's values.
class EnvironmentProfile {
public:
    /// `levels` by strictly increasing height, at least two, each with a finite height and
    /// temperature, the first with a dew point. Missing values are filled in (ours; the
    /// paper has no sounding): dew points by interpolation between given ones, and above the
    /// last given one with its dew-point depression kept; pressures hydrostatically from the
    /// level below (from 1013.25 hPa at sea level when no level has one; levels below the
    /// first with a pressure, downward from it); winds by interpolating the east and north
    /// components between levels that have them (calm when none has). Throws
    /// std::invalid_argument for anything else.
    explicit EnvironmentProfile(std::vector<ProfileLevel> levels);
    /// A profile as stored: every value filled in, and the height of the highest level whose
    /// wind was given (windTopHeight()), which must be -infinity or a level's height.
    EnvironmentProfile(std::vector<ProfileLevel> levels, double windTopHeight);

    const std::vector<ProfileLevel>& levels() const { return mLevels; }
    double groundHeight() const { return mLevels.front().heightM; }
    double topHeight() const { return mLevels.back().heightM; }

    double temperature(double z) const;
    double dewpoint(double z) const;
    double pressure(double z) const;
    Wind wind(double z) const;
    /// The highest level whose wind the source gave: above it wind() holds that level's
    /// wind, which nobody measured (a skew-T draws no barbs there). -infinity when no level
    /// had a wind (calm everywhere).
    double windTopHeight() const { return mWindTop; }

private:
    /// The level i below z and the weight of level i + 1 (0 .. 1, clamped outside).
    std::size_t segment(double z, double& weight) const;

    std::vector<ProfileLevel> mLevels;
    double mWindTop = 0.0;
};

/// The ICAO standard atmosphere from sea level: the temperature falls 6.5 C/km from
/// `surfaceTemperatureC` up to `tropopauseM` and is constant above, to `topM`; the pressure is
/// 1013.25 hPa at sea level and hydrostatic above. The dew point keeps its surface depression
/// (T - T_d) at every height (ours: ICAO's standard atmosphere is dry). Levels every
/// `spacingM` metres (and at the tropopause). No wind.
EnvironmentProfile standardAtmosphere(double surfaceTemperatureC, double surfaceDewpointC,
                                      double tropopauseM, double topM = 20000.0,
                                      double spacingM = 100.0);

}  // namespace cg::algo
