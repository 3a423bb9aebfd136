#include "algo/atmosphere/SkewT.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "algo/atmosphere/SkewTCanvas.h"
#include "algo/atmosphere/SkewTLayers.h"

namespace cg::algo {

namespace {

constexpr std::uint8_t kFrame[3] = {120, 120, 120};
constexpr std::uint8_t kWhite[3] = {255, 255, 255};

void drawFrame(SkewTCanvas& canvas, const SkewTAxes& a)
{
    const int x0 = a.left() - 1, y0 = a.top() - 1, x1 = a.right(), y1 = a.bottom();
    canvas.line(x0, y0, x1, y0, kFrame);
    canvas.line(x0, y1, x1, y1, kFrame);
    canvas.line(x0, y0, x0, y1, kFrame);
    canvas.line(x1, y0, x1, y1, kFrame);
}

void drawTitle(SkewTCanvas& canvas, const SkewTAxes& a, const std::string& title)
{
    const std::string text = title.empty() ? "Skew-T log-p diagram" : title;
    const int scale = SkewTCanvas::textWidth(text, 2) <= canvas.width() - 8 ? 2 : 1;
    canvas.text(text, (canvas.width() - SkewTCanvas::textWidth(text, scale)) / 2,
                (a.top() - SkewTCanvas::kGlyphHeight * scale) / 2, kSkewTText, scale);
}

/// A line sample or a shaded swatch, then its words.
void legendRow(SkewTCanvas& canvas, int x, int y, const std::uint8_t* c, bool swatch,
               const std::string& words)
{
    if (swatch)
        for (int dy = -3; dy <= 3; ++dy)
            for (int dx = 0; dx < 16; ++dx) canvas.blend(x + dx, y + dy, c, kSkewTShadeAlpha);
    else
        canvas.line(x, y, x + 15, y, c, 2);
    canvas.text(words, x + 22, y - 3, kSkewTText);
}

void drawLegend(SkewTCanvas& canvas, const SkewTAxes& a, const ParcelAscent& parcel)
{
    char cape[48], cin[48];
    std::snprintf(cape, sizeof cape, "CAPE %.0f J/kg", parcel.capeJPerKg);
    std::snprintf(cin, sizeof cin, "CIN %.0f J/kg", parcel.cinJPerKg);
    const int x = a.left() + 6, y = a.top() + 14, rows = 6, w = 148, h = 11 * rows + 6;
    canvas.fillRect(x, y, x + w, y + h, kWhite);
    canvas.line(x, y, x + w, y, kFrame);
    canvas.line(x, y + h, x + w, y + h, kFrame);
    canvas.line(x, y, x, y + h, kFrame);
    canvas.line(x + w, y, x + w, y + h, kFrame);
    int row = y + 8;
    legendRow(canvas, x + 6, row, kSkewTEnvironment, false, "Temperature");
    legendRow(canvas, x + 6, row += 11, kSkewTDewpoint, false, "Dew point");
    legendRow(canvas, x + 6, row += 11, kSkewTParcel, false, "Parcel");
    legendRow(canvas, x + 6, row += 11, kSkewTCapeInk, true, cape);
    legendRow(canvas, x + 6, row += 11, kSkewTCinInk, true, cin);
    canvas.polyline({{x + 6.0, row + 11.0}, {x + 21.0, row + 11.0}}, kSkewTMixingRatio, 1, 4, 4);
    canvas.text("Mixing ratio g/kg", x + 28, row + 8, kSkewTText);
}

}  // namespace

SkewTAxes::SkewTAxes(const SkewTOptions& o) : mOptions(o), mPixelsPerLog(0.0), mPixelsPerC(0.0)
{
    const int w = o.width - kLeftMargin - kRightMargin;
    const int h = o.height - kTopMargin - kBottomMargin;
    if (!(w > 0 && h > 0 && o.bottomHPa > o.topHPa && o.topHPa > 0.0 && o.rightC > o.leftC))
        throw std::invalid_argument("skew-T: bad diagram settings");
    mPixelsPerLog = h / std::log(o.bottomHPa / o.topHPa);
    mPixelsPerC = w / (o.rightC - o.leftC);
}

double SkewTAxes::y(double hPa) const
{
    return bottom() - mPixelsPerLog * std::log(mOptions.bottomHPa / hPa);
}

double SkewTAxes::pressure(double y) const
{
    return mOptions.bottomHPa * std::exp(-(bottom() - y) / mPixelsPerLog);
}

double SkewTAxes::x(double c, double hPa) const
{
    // Isotherms lean 45 degrees: one column right for every row up.
    return left() + (c - mOptions.leftC) * mPixelsPerC + (bottom() - y(hPa));
}

double SkewTAxes::temperature(double x, double hPa) const
{
    return mOptions.leftC + (x - left() - (bottom() - y(hPa))) / mPixelsPerC;
}

SkewTImage drawSkewT(const EnvironmentProfile& profile, const ParcelAscent& parcel,
                     const SkewTOptions& o)
{
    const SkewTAxes a(o);
    SkewTCanvas canvas(o.width, o.height);
    skewt::shadeBuoyancy(canvas, a, profile, parcel);
    skewt::drawDryAdiabats(canvas, a);
    skewt::drawMoistAdiabats(canvas, a);
    skewt::drawIsotherms(canvas, a);
    skewt::drawIsobars(canvas, a);
    skewt::drawMixingRatioLines(canvas, a);
    drawFrame(canvas, a);
    skewt::drawSoundingCurves(canvas, a, profile, parcel);
    skewt::drawParcelLevels(canvas, a, profile, parcel);
    skewt::drawWindBarbs(canvas, a, profile);
    drawTitle(canvas, a, o.title);
    drawLegend(canvas, a, parcel);
    return canvas.take();
}

}  // namespace cg::algo
