#pragma once
/// A skew-T log-p diagram: the picture a meteorologist reads a sounding from. The
/// environment's temperature (red) and dew point (green) and the lifted parcel (black) over
/// skewed isotherms (grey, 45 degrees), isobars (grey, labelled in hPa) and dry adiabats
/// (tan); the LCL, LFC and EL as ticks on the right, and a cloud's extent as a blue bar beside
/// them when given. Drawn into an 8-bit RGB raster, no file format.

#include <cstdint>
#include <limits>
#include <vector>

#include "algo/atmosphere/Parcel.h"
#include "algo/atmosphere/Profile.h"

namespace cg::algo {

struct SkewTOptions {
    int width = 640;
    int height = 720;
    double bottomHPa = 1050.0;  ///< the diagram's pressure range
    double topHPa = 100.0;
    double leftC = -40.0;  ///< temperature at the bottom-left corner
    double rightC = 50.0;  ///< temperature at the bottom-right corner
    /// A cloud drawn beside the ticks, base and top above sea level (m); NaN: none.
    double cloudBaseM = std::numeric_limits<double>::quiet_NaN();
    double cloudTopM = std::numeric_limits<double>::quiet_NaN();
};

struct SkewTImage {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgb;  ///< 3 bytes a pixel, top row first
};

/// The diagram's pixel coordinates of temperature `c` at pressure `hPa` (x right, y down).
struct SkewTAxes {
    explicit SkewTAxes(const SkewTOptions& o);
    double x(double c, double hPa) const;
    double y(double hPa) const;

private:
    SkewTOptions mOptions;
    double mPixelsPerLog;  ///< rows per unit of ln(bottom / p)
    double mPixelsPerC;
};

constexpr std::uint8_t kSkewTEnvironment[3] = {200, 30, 30};
constexpr std::uint8_t kSkewTDewpoint[3] = {20, 150, 40};
constexpr std::uint8_t kSkewTParcel[3] = {0, 0, 0};
constexpr std::uint8_t kSkewTCloud[3] = {90, 130, 200};

SkewTImage drawSkewT(const EnvironmentProfile& profile, const ParcelAscent& parcel,
                     const SkewTOptions& options = {});

}  // namespace cg::algo
