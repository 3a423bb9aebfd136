#pragma once
/// A horizontal wind that depends on height (issue 14; the paper ignores wind, Sec. 7 asks for
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

private:
    std::vector<WindLevel> mLevels;
};

/// The east and north components of a wind of `speed` blowing from `fromDegrees`.
Wind windFromDirection(double speed, double fromDegrees);

}  // namespace cg::algo
