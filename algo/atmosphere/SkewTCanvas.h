#pragma once
/// The raster the skew-T diagram is drawn on: white paper, pixels, straight and dashed lines,
/// translucent fills and text in a built-in 5 x 7 pixel font (printable ASCII; a glyph cell is
/// 6 x 8 pixels at scale 1). Everything is clipped to the image; nothing is anti-aliased, so
/// the same input always gives the same pixels.

#include <cstdint>
#include <string>
#include <vector>

#include "algo/atmosphere/SkewT.h"

namespace cg::algo {

struct SkewTPoint {
    double x = 0.0;
    double y = 0.0;
};

class SkewTCanvas {
public:
    SkewTCanvas(int width, int height);

    int width() const { return mImage.width; }
    int height() const { return mImage.height; }

    /// Confines drawing to the rectangle from (x0, y0) to (x1, y1) inclusive until clip() is
    /// called again or unclip() lifts it.
    void clip(int x0, int y0, int x1, int y1);
    void unclip() { clip(0, 0, mImage.width - 1, mImage.height - 1); }

    void dot(int x, int y, const std::uint8_t* c);
    /// `c` laid at `alpha` (0 .. 1) over what the pixel holds.
    void blend(int x, int y, const std::uint8_t* c, double alpha);
    void fillRect(int x0, int y0, int x1, int y1, const std::uint8_t* c);  ///< inclusive
    /// A line `thickness` pixels wide (a square brush).
    void line(double x0, double y0, double x1, double y1, const std::uint8_t* c, int thickness = 1);
    /// Points joined by lines; with dash > 0, drawn `dash` pixels on and `gap` off along the
    /// whole path.
    void polyline(const std::vector<SkewTPoint>& points, const std::uint8_t* c, int thickness = 1,
                  int dash = 0, int gap = 0);
    /// A filled triangle.
    void triangle(SkewTPoint a, SkewTPoint b, SkewTPoint c, const std::uint8_t* colour);

    /// `text` with its top-left at (x, y), each font pixel `scale` x `scale`.
    void text(const std::string& text, int x, int y, const std::uint8_t* c, int scale = 1);
    /// The same on a white box one pixel larger all round, so it reads over lines.
    void label(const std::string& text, int x, int y, const std::uint8_t* c, int scale = 1);
    static int textWidth(const std::string& text, int scale = 1);
    static constexpr int kGlyphHeight = 7;

    SkewTImage take() { return std::move(mImage); }

private:
    bool inside(int x, int y) const
    {
        return x >= mClipX0 && y >= mClipY0 && x <= mClipX1 && y <= mClipY1;
    }

    SkewTImage mImage;
    int mClipX0 = 0, mClipY0 = 0, mClipX1 = -1, mClipY1 = -1;
};

}  // namespace cg::algo
