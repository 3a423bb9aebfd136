#pragma once
/// From linear scene radiance to display values: exposure, a filmic curve, the sRGB encoding.
/// All functions are per channel and map to [0, 1]; NaN becomes 0.

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace cg::algo {

enum class ToneCurve {
    Aces,   ///< Narkowicz's fit of the ACES RRT+ODT (2015), input pre-scaled by 0.6
    Hable,  ///< Hable's "Uncharted 2" filmic curve, white point 11.2
    Clamp,  ///< no curve: clamp to [0, 1]
};

/// Parses "aces", "hable" or "clamp"; throws std::invalid_argument otherwise.
inline ToneCurve toneCurveFromName(const std::string& name)
{
    if (name == "aces") return ToneCurve::Aces;
    if (name == "hable") return ToneCurve::Hable;
    if (name == "clamp") return ToneCurve::Clamp;
    throw std::invalid_argument("unknown tone curve '" + name + "'");
}

/// Narkowicz 2015 ACES fit; 0.6 scales linear sRGB-primaries radiance into the fit's range.
inline double acesFitted(double x)
{
    x *= 0.6;
    return (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
}

/// Hable 2010 filmic curve, normalised so that the white point W = 11.2 maps to 1.
inline double hableFilmic(double x)
{
    const auto f = [](double v) {
        constexpr double A = 0.15, B = 0.50, C = 0.10, D = 0.20, E = 0.02, F = 0.30;
        return ((v * (A * v + C * B) + D * E) / (v * (A * v + B) + D * F)) - E / F;
    };
    return f(2.0 * x) / f(11.2);  // 2: Hable's exposure bias
}

/// Applies the curve to a linear value already multiplied by the exposure; result in [0, 1].
inline double toneMap(double x, ToneCurve curve)
{
    if (!(x > 0.0)) return 0.0;  // also NaN
    double y = x;
    switch (curve) {
        case ToneCurve::Aces:
            y = acesFitted(x);
            break;
        case ToneCurve::Hable:
            y = hableFilmic(x);
            break;
        case ToneCurve::Clamp:
            break;
    }
    return std::clamp(y, 0.0, 1.0);
}

/// The sRGB transfer function (IEC 61966-2-1): linear [0, 1] to encoded [0, 1].
inline double srgbEncode(double linear)
{
    if (!(linear > 0.0)) return 0.0;
    if (linear >= 1.0) return 1.0;
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

/// Inverse of srgbEncode.
inline double srgbDecode(double encoded)
{
    if (!(encoded > 0.0)) return 0.0;
    if (encoded >= 1.0) return 1.0;
    return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

}  // namespace cg::algo
