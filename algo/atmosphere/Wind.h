#pragma once
/// A horizontal wind that depends on height (the paper ignores wind, Sec. 7 asks for
/// it). Heights are above the ground in metres, winds in m/s toward the east and the north.

#include <vector>

#include "algo/atmosphere/Profile.h"

namespace cg::algo {

struct WindLevel {
    double heightM = 0.0;
    double east = 0.0;
    double north = 0.0;
};

/// Linear in height between levels, held below the first and above the last. No levels: calm.
class WindProfile {
public:
    WindProfile() = default;
    /// `levels` by strictly increasing height with finite values; throws std::invalid_argument
    /// otherwise.
    explicit WindProfile(std::vector<WindLevel> levels);

    /// Speed (m/s) and the direction it blows from (degrees clockwise from north, as sondes
    /// and weather maps give it) at each height: a wind from 270 blows toward the east.
    static WindProfile fromSpeedAndDirection(const std::vector<double>& heightsM,
                                             const std::vector<double>& speedsMs,
                                             const std::vector<double>& fromDegrees);

    bool calm() const { return mLevels.empty(); }
    const std::vector<WindLevel>& levels() const { return mLevels; }
    Wind at(double heightM) const;
    /// The mean wind between the ground and `topM` (the integral of at() over height divided by
    /// topM, exact for the piecewise-linear profile); calm for topM <= 0.
    Wind meanBelow(double topM) const;
    /// The same winds seen from a frame that moves at `motion` (every level minus it).
    WindProfile relativeTo(Wind motion) const;

private:
    std::vector<WindLevel> mLevels;
};

/// Depth of the layer whose mean wind estimates an ordinary storm's motion (the 0-6 km mean
/// wind; supercells deviate from it, Bunkers et al. 2000).
inline constexpr double kStormSteeringDepthM = 6000.0;

/// The east and north components of a wind of `speed` blowing from `fromDegrees`.
Wind windFromDirection(double speed, double fromDegrees);

}  // namespace cg::algo
