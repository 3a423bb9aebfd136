#pragma once
/// A skew-T log-p diagram: the picture a meteorologist reads a sounding from, laid out as
/// MetPy's SkewT. The environment's temperature (red) and dew point (green) and the parcel
/// lifted from the ground (black) over isotherms leaning 45 degrees (grey, every 10 C,
/// labelled along the temperature axis at the bottom and where they leave the top), isobars
/// (grey, labelled in hPa on the left), dry adiabats (tan, every 10 K), moist adiabats (light
/// blue, every 5 C at 1000 hPa, up to 200 hPa) and mixing-ratio lines (dashed green, labelled
/// in g/kg at 600 hPa). The parcel's CAPE (warmer than the environment from the LFC to the EL)
/// is shaded translucent red, its CIN (colder, below the LFC) translucent blue; the LCL, LFC
/// and EL are labelled ticks on the plot's right edge, a cloud's extent a blue bar beside them;
/// wind barbs by height (knots: half barb 5, barb 10, pennant 50) stand right of the plot where
/// the profile has wind. A title above and a legend (with CAPE and CIN in J/kg) in the upper
/// left. Drawn into an 8-bit RGB raster with a built-in 5 x 7 pixel font, no file format.

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "algo/atmosphere/Parcel.h"
#include "algo/atmosphere/Profile.h"

namespace cg::algo {

struct SkewTOptions {
    int width = 640;  ///< the whole image; the plot leaves margins for labels and barbs
    int height = 720;
    double bottomHPa = 1050.0;  ///< the plot's pressure range
    double topHPa = 100.0;
    double leftC = -40.0;  ///< temperature at the plot's bottom-left corner
    double rightC = 50.0;  ///< temperature at the plot's bottom-right corner
    /// A cloud drawn beside the ticks, base and top above sea level (m); NaN: none.
    double cloudBaseM = std::numeric_limits<double>::quiet_NaN();
    double cloudTopM = std::numeric_limits<double>::quiet_NaN();
    std::string title;  ///< above the plot; empty: "Skew-T log-p diagram"
};

struct SkewTImage {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgb;  ///< 3 bytes a pixel, top row first
};

/// Where the plot lies in the image, and the image's pixel coordinates of temperature `c` at
/// pressure `hPa` (x right, y down): y logarithmic in pressure, isotherms at 45 degrees.
struct SkewTAxes {
    /// Margins: left for pressure labels, top for the title, right for the wind barbs, bottom
    /// for the temperature axis. Throws std::invalid_argument for settings that leave no plot.
    static constexpr int kLeftMargin = 44;
    static constexpr int kTopMargin = 30;
    static constexpr int kRightMargin = 68;
    static constexpr int kBottomMargin = 28;

    explicit SkewTAxes(const SkewTOptions& o);
    double x(double c, double hPa) const;
    double y(double hPa) const;
    double pressure(double y) const;  ///< the inverse of y
    /// The temperature (C) at pixel column x on isobar hPa: the inverse of x.
    double temperature(double x, double hPa) const;

    int left() const { return kLeftMargin; }
    int top() const { return kTopMargin; }
    int right() const { return mOptions.width - kRightMargin; }  ///< one past the plot
    int bottom() const { return mOptions.height - kBottomMargin; }
    const SkewTOptions& options() const { return mOptions; }

private:
    SkewTOptions mOptions;
    double mPixelsPerLog;  ///< rows per unit of ln(bottom / p)
    double mPixelsPerC;
};

constexpr std::uint8_t kSkewTEnvironment[3] = {200, 30, 30};
constexpr std::uint8_t kSkewTDewpoint[3] = {20, 150, 40};
constexpr std::uint8_t kSkewTParcel[3] = {0, 0, 0};
constexpr std::uint8_t kSkewTCloud[3] = {90, 130, 200};
constexpr std::uint8_t kSkewTIsotherm[3] = {205, 205, 205};
constexpr std::uint8_t kSkewTDryAdiabat[3] = {225, 190, 140};
constexpr std::uint8_t kSkewTMoistAdiabat[3] = {150, 185, 230};
constexpr std::uint8_t kSkewTMixingRatio[3] = {110, 185, 125};
constexpr std::uint8_t kSkewTText[3] = {60, 60, 60};
constexpr std::uint8_t kSkewTBarb[3] = {30, 30, 90};
/// The CAPE and CIN shades: red and blue laid at kSkewTShadeAlpha over the paper.
constexpr std::uint8_t kSkewTCapeInk[3] = {220, 40, 40};
constexpr std::uint8_t kSkewTCinInk[3] = {40, 80, 220};
constexpr double kSkewTShadeAlpha = 0.3;

/// `ink` laid at `alpha` over `paper`, rounded: how a translucent shade colours a pixel.
constexpr std::uint8_t skewTBlend(std::uint8_t paper, std::uint8_t ink, double alpha)
{
    return static_cast<std::uint8_t>(paper + alpha * (ink - paper) + 0.5);
}

/// The shades as they appear over white paper.
constexpr std::uint8_t kSkewTCape[3] = {skewTBlend(255, kSkewTCapeInk[0], kSkewTShadeAlpha),
                                        skewTBlend(255, kSkewTCapeInk[1], kSkewTShadeAlpha),
                                        skewTBlend(255, kSkewTCapeInk[2], kSkewTShadeAlpha)};
constexpr std::uint8_t kSkewTCin[3] = {skewTBlend(255, kSkewTCinInk[0], kSkewTShadeAlpha),
                                       skewTBlend(255, kSkewTCinInk[1], kSkewTShadeAlpha),
                                       skewTBlend(255, kSkewTCinInk[2], kSkewTShadeAlpha)};

SkewTImage drawSkewT(const EnvironmentProfile& profile, const ParcelAscent& parcel,
                     const SkewTOptions& options = {});

}  // namespace cg::algo
