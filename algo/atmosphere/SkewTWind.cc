// The skew-T's wind barbs (SkewTLayers.h), drawn the way weather maps draw them.

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "algo/atmosphere/SkewTLayers.h"

namespace cg::algo::skewt {

namespace {

constexpr double kKnotsPerMs = 1.0 / 0.514444;
constexpr double kFeather = 10.0;  ///< a full barb's length, pixels
constexpr double kSpacing = 4.0;   ///< between barbs along the staff, pixels

SkewTPoint along(SkewTPoint p, SkewTPoint d, double s) { return {p.x + s * d.x, p.y + s * d.y}; }

}  // namespace

void drawWindBarb(SkewTCanvas& canvas, SkewTPoint base, Wind wind, double length)
{
    const double speed = std::hypot(wind.east, wind.north);
    const int knots = 5 * static_cast<int>(std::lround(speed * kKnotsPerMs / 5.0));
    if (knots == 0) return;  // calm
    // Screen directions (y down): the staff toward where the wind blows from, the barbs on its
    // clockwise side, leaning out toward the staff's tip.
    const SkewTPoint d{-wind.east / speed, wind.north / speed};
    const SkewTPoint side{-wind.north / speed, -wind.east / speed};
    const SkewTPoint feather{0.87 * side.x + 0.5 * d.x, 0.87 * side.y + 0.5 * d.y};
    const SkewTPoint tip = along(base, d, length);
    canvas.line(base.x, base.y, tip.x, tip.y, kSkewTBarb, 2);
    canvas.line(base.x - 1, base.y - 1, base.x + 1, base.y + 1, kSkewTBarb, 2);  // the station

    double s = 0.0;  // distance of the next mark from the tip toward the base
    int left = knots;
    for (; left >= 50; left -= 50, s += 8.0) {
        const SkewTPoint p = along(tip, d, -s);
        canvas.triangle(p, along(p, d, -6.0), along(p, side, kFeather), kSkewTBarb);
    }
    for (; left >= 10; left -= 10, s += kSpacing) {
        const SkewTPoint p = along(tip, d, -s);
        canvas.line(p.x, p.y, p.x + kFeather * feather.x, p.y + kFeather * feather.y, kSkewTBarb);
    }
    if (left >= 5) {
        if (knots == 5) s = kSpacing;  // a lone half barb stands off the tip
        const SkewTPoint p = along(tip, d, -s);
        canvas.line(p.x, p.y, p.x + 0.5 * kFeather * feather.x, p.y + 0.5 * kFeather * feather.y,
                    kSkewTBarb);
    }
}

void drawWindBarbs(SkewTCanvas& canvas, const SkewTAxes& a, const EnvironmentProfile& profile)
{
    const double x = a.right() + 34.0;
    const std::string title = "Wind (kt)";
    canvas.text(title, static_cast<int>(x) - SkewTCanvas::textWidth(title) / 2, a.top() - 11,
                kSkewTText);
    double lastY = std::numeric_limits<double>::infinity();
    // Barbs only where the sounding measured wind: above its highest wind the profile holds
    // that wind, which no one observed.
    const double top = std::min(profile.topHeight(), profile.windTopHeight());
    for (double z = profile.groundHeight(); z <= top; z += 10.0) {
        const double y = a.y(profile.pressure(z));
        if (y >= a.bottom()) continue;
        if (y < a.top() + 4.0) break;
        if (lastY - y < 24.0) continue;
        drawWindBarb(canvas, {x, y}, profile.wind(z));
        lastY = y;
    }
}

}  // namespace cg::algo::skewt
