// The skew-T's data (SkewTLayers.h): the sounding's curves, the parcel, its energy and levels.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "algo/atmosphere/SkewTLayers.h"

namespace cg::algo::skewt {

namespace {

/// The shade of one row: CAPE above the LFC where the parcel is warmer, CIN below it where
/// it is colder; null for none.
const std::uint8_t* buoyancyShade(const ParcelAscent& parcel, double z, double parcelC,
                                  double environmentC)
{
    if (z >= parcel.lfcM && z <= parcel.elM && parcelC > environmentC) return kSkewTCapeInk;
    if (z < parcel.lfcM && parcelC < environmentC) return kSkewTCinInk;
    return nullptr;
}

/// Shades, in each pixel row between two points of the parcel's path, the columns between
/// the parcel's and the environment's temperatures.
void shadeSegment(SkewTCanvas& canvas, const SkewTAxes& a, const ParcelAscent& parcel,
                  const ParcelPoint& q0, const ParcelPoint& q1, double y0, double y1)
{
    // Rows y1 < row <= y0 (y grows downward), so each row is shaded by one segment only.
    for (int row = static_cast<int>(std::floor(y0)); row > y1; --row) {
        const double t = (y0 - row) / (y0 - y1);
        const double z = q0.heightM + t * (q1.heightM - q0.heightM);
        const double tp = q0.parcelC + t * (q1.parcelC - q0.parcelC);
        const double te = q0.environmentC + t * (q1.environmentC - q0.environmentC);
        const std::uint8_t* shade = buoyancyShade(parcel, z, tp, te);
        if (!shade) continue;
        const double p = a.pressure(row);
        const long x0 = std::lround(a.x(std::min(tp, te), p));
        const long x1 = std::lround(a.x(std::max(tp, te), p));
        for (long x = x0; x <= x1; ++x)
            canvas.blend(static_cast<int>(x), row, shade, kSkewTShadeAlpha);
    }
}

struct LevelMark {
    const char* name;
    double heightM;
};

}  // namespace

void shadeBuoyancy(SkewTCanvas& canvas, const SkewTAxes& a, const EnvironmentProfile& profile,
                   const ParcelAscent& parcel)
{
    if (!std::isfinite(parcel.lfcM)) return;
    canvas.clip(a.left(), a.top(), a.right() - 1, a.bottom() - 1);
    const auto& path = parcel.path;
    for (std::size_t i = 1; i < path.size(); ++i) {
        const double y0 = a.y(profile.pressure(path[i - 1].heightM));
        const double y1 = a.y(profile.pressure(path[i].heightM));
        if (y1 < y0) shadeSegment(canvas, a, parcel, path[i - 1], path[i], y0, y1);
    }
    canvas.unclip();
}

void drawSoundingCurves(SkewTCanvas& canvas, const SkewTAxes& a, const EnvironmentProfile& profile,
                        const ParcelAscent& parcel)
{
    canvas.clip(a.left(), a.top(), a.right() - 1, a.bottom() - 1);
    std::vector<SkewTPoint> temperature, dewpoint, lifted;
    for (const ProfileLevel& l : profile.levels()) {
        temperature.push_back({a.x(l.temperatureC, l.pressureHPa), a.y(l.pressureHPa)});
        dewpoint.push_back({a.x(l.dewpointC, l.pressureHPa), a.y(l.pressureHPa)});
    }
    for (const ParcelPoint& q : parcel.path) {
        const double p = profile.pressure(q.heightM);
        lifted.push_back({a.x(q.parcelC, p), a.y(p)});
    }
    canvas.polyline(dewpoint, kSkewTDewpoint, 2);
    canvas.polyline(temperature, kSkewTEnvironment, 2);
    canvas.polyline(lifted, kSkewTParcel, 2);
    canvas.unclip();
}

void drawParcelLevels(SkewTCanvas& canvas, const SkewTAxes& a, const EnvironmentProfile& profile,
                      const ParcelAscent& parcel)
{
    const SkewTOptions& o = a.options();
    const int right = a.right() - 1;
    if (std::isfinite(o.cloudBaseM) && std::isfinite(o.cloudTopM) && o.cloudTopM >= o.cloudBaseM) {
        canvas.clip(a.left(), a.top(), a.right() - 1, a.bottom() - 1);
        const double yBase = a.y(profile.pressure(o.cloudBaseM));
        const double yTop = a.y(profile.pressure(o.cloudTopM));
        for (int x = right - 80; x < right - 70; ++x) canvas.line(x, yBase, x, yTop, kSkewTCloud);
        canvas.unclip();
    }
    // From the bottom up; a label never closer than 10 pixels above the one below it.
    double labelY = a.bottom() + 10.0;
    for (const LevelMark& m : {LevelMark{"LCL", parcel.lclM}, LevelMark{"LFC", parcel.lfcM},
                               LevelMark{"EL", parcel.elM}}) {
        if (!std::isfinite(m.heightM)) continue;
        const double p = profile.pressure(m.heightM);
        const double y = a.y(p);
        if (y < a.top() || y >= a.bottom()) continue;
        canvas.line(right - 20, y, right, y, kSkewTParcel, 2);
        char text[32];
        std::snprintf(text, sizeof text, "%s %.0f", m.name, p);
        labelY = std::min(y - 3.0, labelY - 10.0);
        canvas.label(text, right - 24 - SkewTCanvas::textWidth(text),
                     static_cast<int>(std::lround(labelY)), kSkewTParcel);
    }
}

}  // namespace cg::algo::skewt
