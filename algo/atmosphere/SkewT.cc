#include "algo/atmosphere/SkewT.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "algo/atmosphere/Thermodynamics.h"

namespace cg::algo {

namespace {

constexpr std::uint8_t kGrid[3] = {205, 205, 205};
constexpr std::uint8_t kAdiabat[3] = {225, 195, 150};
constexpr std::uint8_t kLabel[3] = {90, 90, 90};

/// Digits 0-9, 3 x 5 pixels, a row per 3 bits (most significant bit left).
constexpr std::uint8_t kDigits[10][5] = {
    {7, 5, 5, 5, 7}, {2, 6, 2, 2, 7}, {7, 1, 7, 4, 7}, {7, 1, 7, 1, 7}, {5, 5, 7, 1, 1},
    {7, 4, 7, 1, 7}, {7, 4, 7, 5, 7}, {7, 1, 1, 1, 1}, {7, 5, 7, 5, 7}, {7, 5, 7, 1, 7}};

class Canvas {
public:
    Canvas(int width, int height)
        : mImage{width, height, std::vector<std::uint8_t>(3u * width * height, 255)}
    {
    }

    void dot(int x, int y, const std::uint8_t* c)
    {
        if (x < 0 || y < 0 || x >= mImage.width || y >= mImage.height) return;
        std::uint8_t* p = &mImage.rgb[3u * (static_cast<std::size_t>(y) * mImage.width + x)];
        p[0] = c[0], p[1] = c[1], p[2] = c[2];
    }

    /// A line `thickness` pixels wide (a square brush), clipped to the canvas.
    void line(double x0, double y0, double x1, double y1, const std::uint8_t* c, int thickness = 1)
    {
        const int steps =
            static_cast<int>(std::ceil(std::max(std::fabs(x1 - x0), std::fabs(y1 - y0)))) + 1;
        if (steps > 100000) return;  // off any sane canvas
        for (int k = 0; k <= steps; ++k) {
            const double t = static_cast<double>(k) / steps;
            const int x = static_cast<int>(std::lround(x0 + t * (x1 - x0)));
            const int y = static_cast<int>(std::lround(y0 + t * (y1 - y0)));
            for (int dy = 0; dy < thickness; ++dy)
                for (int dx = 0; dx < thickness; ++dx)
                    dot(x + dx - thickness / 2, y + dy - thickness / 2, c);
        }
    }

    /// A whole number in 3 x 5 digits, scaled 2x, its top-left at (x, y).
    void number(int value, int x, int y)
    {
        char text[16];
        std::snprintf(text, sizeof text, "%d", value);
        for (const char* ch = text; *ch; ++ch, x += 8) {
            if (*ch < '0' || *ch > '9') continue;
            const auto& glyph = kDigits[*ch - '0'];
            for (int row = 0; row < 5; ++row)
                for (int col = 0; col < 3; ++col)
                    if (glyph[row] & (4 >> col))
                        for (int s = 0; s < 4; ++s)
                            dot(x + 2 * col + s % 2, y + 2 * row + s / 2, kLabel);
        }
    }

    SkewTImage take() { return std::move(mImage); }

private:
    SkewTImage mImage;
};

}  // namespace

SkewTAxes::SkewTAxes(const SkewTOptions& o)
    : mOptions(o),
      mPixelsPerLog(o.height / std::log(o.bottomHPa / o.topHPa)),
      mPixelsPerC(o.width / (o.rightC - o.leftC))
{
    if (!(o.width > 0 && o.height > 0 && o.bottomHPa > o.topHPa && o.topHPa > 0.0 &&
          o.rightC > o.leftC))
        throw std::invalid_argument("skew-T: bad diagram settings");
}

double SkewTAxes::y(double hPa) const
{
    return mOptions.height - mPixelsPerLog * std::log(mOptions.bottomHPa / hPa);
}

double SkewTAxes::x(double c, double hPa) const
{
    // Isotherms lean 45 degrees: one column right for every row up.
    return (c - mOptions.leftC) * mPixelsPerC + (mOptions.height - y(hPa));
}

SkewTImage drawSkewT(const EnvironmentProfile& profile, const ParcelAscent& parcel,
                     const SkewTOptions& o)
{
    const SkewTAxes a(o);
    Canvas canvas(o.width, o.height);
    // Dry adiabats: potential temperature theta kept, T = theta (p / 1000)^(R_d / c_pd).
    const double kappa = thermo::kDryGasConstant / thermo::kDryHeatCapacity;
    for (double theta = -30.0; theta <= 200.0; theta += 10.0)
        for (double p = o.bottomHPa; p > o.topHPa; p -= 10.0) {
            const auto t = [&](double q) {
                return (theta + thermo::kKelvin) * std::pow(q / 1000.0, kappa) - thermo::kKelvin;
            };
            canvas.line(a.x(t(p), p), a.y(p), a.x(t(p - 10.0), p - 10.0), a.y(p - 10.0), kAdiabat);
        }
    for (double c = -120.0; c <= o.rightC; c += 10.0)
        canvas.line(a.x(c, o.bottomHPa), a.y(o.bottomHPa), a.x(c, o.topHPa), a.y(o.topHPa), kGrid);
    for (int p = 1000; p >= o.topHPa; p -= 100) {
        canvas.line(0, a.y(p), o.width - 1, a.y(p), kGrid);
        canvas.number(p, 4, static_cast<int>(a.y(p)) - 12);
    }

    // The sounding, level by level (the profile interpolates linearly in height).
    const auto& levels = profile.levels();
    for (std::size_t i = 1; i < levels.size(); ++i) {
        const ProfileLevel& l0 = levels[i - 1];
        const ProfileLevel& l1 = levels[i];
        canvas.line(a.x(l0.dewpointC, l0.pressureHPa), a.y(l0.pressureHPa),
                    a.x(l1.dewpointC, l1.pressureHPa), a.y(l1.pressureHPa), kSkewTDewpoint, 2);
        canvas.line(a.x(l0.temperatureC, l0.pressureHPa), a.y(l0.pressureHPa),
                    a.x(l1.temperatureC, l1.pressureHPa), a.y(l1.pressureHPa), kSkewTEnvironment,
                    2);
    }
    for (std::size_t i = 1; i < parcel.path.size(); ++i) {
        const ParcelPoint& q0 = parcel.path[i - 1];
        const ParcelPoint& q1 = parcel.path[i];
        const double p0 = profile.pressure(q0.heightM), p1 = profile.pressure(q1.heightM);
        canvas.line(a.x(q0.parcelC, p0), a.y(p0), a.x(q1.parcelC, p1), a.y(p1), kSkewTParcel);
    }

    // LCL, LFC and EL as ticks at the right edge; the cloud as a bar beside them.
    const int right = o.width - 1;
    for (double z : {parcel.lclM, parcel.lfcM, parcel.elM})
        if (std::isfinite(z)) {
            const double y = a.y(profile.pressure(z));
            canvas.line(right - 30, y, right, y, kSkewTParcel, 2);
        }
    if (std::isfinite(o.cloudBaseM) && std::isfinite(o.cloudTopM) && o.cloudTopM >= o.cloudBaseM) {
        const double yBase = a.y(profile.pressure(o.cloudBaseM));
        const double yTop = a.y(profile.pressure(o.cloudTopM));
        for (int x = right - 50; x < right - 38; ++x) canvas.line(x, yBase, x, yTop, kSkewTCloud);
    }
    return canvas.take();
}

}  // namespace cg::algo
