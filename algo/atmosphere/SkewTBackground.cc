// The skew-T's reference lines and axes (SkewTLayers.h): what a sounding is read against.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "algo/atmosphere/Convective.h"
#include "algo/atmosphere/SkewTLayers.h"
#include "algo/atmosphere/Thermodynamics.h"

namespace cg::algo::skewt {

namespace {

constexpr std::uint8_t kFreezing[3] = {140, 160, 205};

std::string format(const char* pattern, double value)
{
    char text[32];
    std::snprintf(text, sizeof text, pattern, value);
    return text;
}

/// Confines the canvas to the plot (the reference lines stay inside it).
void clipToPlot(SkewTCanvas& canvas, const SkewTAxes& a)
{
    canvas.clip(a.left(), a.top(), a.right() - 1, a.bottom() - 1);
}

/// A curve T(p) sampled every `stepHPa` from `fromHPa` up to `toHPa`.
template <class Temperature>
std::vector<SkewTPoint> curve(const SkewTAxes& a, double fromHPa, double toHPa, double stepHPa,
                              Temperature t)
{
    std::vector<SkewTPoint> points;
    for (double p = fromHPa; p > toHPa - 1e-9; p -= stepHPa)
        points.push_back({a.x(t(p), p), a.y(p)});
    return points;
}

void labelIsotherm(SkewTCanvas& canvas, const SkewTAxes& a, double c)
{
    const std::string text = format("%.0f", c);
    const int w = SkewTCanvas::textWidth(text);
    const SkewTOptions& o = a.options();
    const double xBottom = a.x(c, o.bottomHPa);
    if (c >= o.leftC && c <= o.rightC) {  // on the temperature axis
        canvas.line(xBottom, a.bottom(), xBottom, a.bottom() + 3, kSkewTText);
        canvas.text(text, static_cast<int>(std::lround(xBottom)) - w / 2, a.bottom() + 5,
                    kSkewTText);
    }
    const double xTop = a.x(c, o.topHPa);
    const int half = w / 2;  // whole pixels: the label's left edge is an integer column
    if (xTop - half - 1 >= a.left() && xTop + half + 1 < a.right())  // where it leaves the top
        canvas.label(text, static_cast<int>(std::lround(xTop)) - w / 2, a.top() + 3, kSkewTText);
}

/// A saturated parcel's temperature `dp` hPa from (t, p): dT/dp = Gamma_m R_d T / (g p), one
/// midpoint step.
double moistStep(double t, double p, double dp)
{
    const auto slope = [](double tc, double hPa) {
        return thermo::moistAdiabaticLapse(tc, hPa) * thermo::kDryGasConstant *
               (tc + thermo::kKelvin) / (thermo::kGravity * hPa);
    };
    return t + dp * slope(t + 0.5 * dp * slope(t, p), p + 0.5 * dp);
}

}  // namespace

void drawIsotherms(SkewTCanvas& canvas, const SkewTAxes& a)
{
    const SkewTOptions& o = a.options();
    // Every isotherm that crosses the plot: the coldest leaves its top-left corner.
    const double coldest = a.temperature(a.left(), o.topHPa);
    clipToPlot(canvas, a);
    for (double c = 10.0 * std::ceil(coldest / 10.0); c <= o.rightC; c += 10.0)
        canvas.line(a.x(c, o.bottomHPa), a.y(o.bottomHPa), a.x(c, o.topHPa), a.y(o.topHPa),
                    c == 0.0 ? kFreezing : kSkewTIsotherm);
    canvas.unclip();
    for (double c = 10.0 * std::ceil(coldest / 10.0); c <= o.rightC; c += 10.0)
        labelIsotherm(canvas, a, c);
    const std::string axis = "Temperature (C)";
    canvas.text(axis, (a.left() + a.right() - SkewTCanvas::textWidth(axis)) / 2, a.bottom() + 17,
                kSkewTText);
}

void drawIsobars(SkewTCanvas& canvas, const SkewTAxes& a)
{
    const SkewTOptions& o = a.options();
    for (double p = 1000.0; p >= o.topHPa - 1e-9; p -= 100.0) {
        if (p > o.bottomHPa) continue;
        const double y = a.y(p);
        canvas.line(a.left(), y, a.right() - 1, y, kSkewTIsotherm);
        const std::string text = format("%.0f", p);
        canvas.text(text, a.left() - 4 - SkewTCanvas::textWidth(text),
                    static_cast<int>(std::lround(y)) - 3, kSkewTText);
    }
    canvas.text("hPa", a.left() - 4 - SkewTCanvas::textWidth("hPa"), a.top() - 11, kSkewTText);
}

void drawDryAdiabats(SkewTCanvas& canvas, const SkewTAxes& a)
{
    const SkewTOptions& o = a.options();
    const double kappa = thermo::kDryGasConstant / thermo::kDryHeatCapacity;
    clipToPlot(canvas, a);
    for (double theta = -30.0; theta <= 200.0; theta += 10.0)
        canvas.polyline(curve(a, o.bottomHPa, o.topHPa, 10.0,
                              [&](double p) {
                                  return (theta + thermo::kKelvin) * std::pow(p / 1000.0, kappa) -
                                         thermo::kKelvin;
                              }),
                        kSkewTDryAdiabat);
    canvas.unclip();
}

double moistAdiabatTemperature(double t1000, double hPa)
{
    const int steps = static_cast<int>(std::ceil(std::fabs(hPa - 1000.0) / 5.0));
    const double dp = steps > 0 ? (hPa - 1000.0) / steps : 0.0;
    double t = t1000;
    for (int k = 0; k < steps; ++k) t = moistStep(t, 1000.0 + k * dp, dp);
    return t;
}

void drawMoistAdiabats(SkewTCanvas& canvas, const SkewTAxes& a)
{
    const SkewTOptions& o = a.options();
    const double top = std::max(200.0, o.topHPa);
    const int steps = static_cast<int>(std::ceil((o.bottomHPa - top) / 5.0));
    const double dp = (top - o.bottomHPa) / steps;
    clipToPlot(canvas, a);
    for (double t1000 = -15.0; t1000 <= 40.0; t1000 += 5.0) {
        // Integrated once along the line from its bottom.
        std::vector<SkewTPoint> points;
        double t = moistAdiabatTemperature(t1000, o.bottomHPa);
        for (int k = 0; k <= steps; ++k) {
            const double p = o.bottomHPa + k * dp;
            points.push_back({a.x(t, p), a.y(p)});
            t = moistStep(t, p, dp);
        }
        canvas.polyline(points, kSkewTMoistAdiabat, 1, 5, 3);
    }
    canvas.unclip();
}

void drawMixingRatioLines(SkewTCanvas& canvas, const SkewTAxes& a)
{
    const SkewTOptions& o = a.options();
    const double top = std::max(600.0, o.topHPa);
    for (double g : {0.4, 1.0, 2.0, 3.0, 5.0, 8.0, 12.0, 16.0, 20.0, 28.0}) {
        const auto dewpoint = [&](double p) { return mixingRatioDewpoint(g * 1e-3, p); };
        clipToPlot(canvas, a);
        canvas.polyline(curve(a, o.bottomHPa, top, 10.0, dewpoint), kSkewTMixingRatio, 1, 4, 4);
        canvas.unclip();
        const std::string text = format("%g", g);
        const double x = a.x(dewpoint(top), top);
        const int w = SkewTCanvas::textWidth(text);
        const int half = w / 2;  // whole pixels, as the label is placed
        if (x - half - 1 >= a.left() && x + half + 1 < a.right())
            canvas.label(text, static_cast<int>(std::lround(x)) - w / 2,
                         static_cast<int>(std::lround(a.y(top))) - 10, kSkewTMixingRatio);
    }
}

}  // namespace cg::algo::skewt
