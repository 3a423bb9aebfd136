#include "algo/volume/OutlineDimension.h"

#include <cmath>
#include <stdexcept>

namespace cg::algo {

namespace {

/// How many s x s boxes of the grid anchored at (0, 0) hold a set pixel (`outline` false),
/// or a piece of the outline (`outline` true): an edge between a set and an unset pixel,
/// counted in the box of the pixel above or left of it, so that an edge lying on a box
/// border is counted once, whatever the alignment of the region to the boxes.
std::size_t countBoxes(const Mask2D& mask, int s, bool outline)
{
    const int across = (mask.width + s - 1) / s;
    const int down = (mask.height + s - 1) / s;
    std::vector<std::uint8_t> marked(
        static_cast<std::size_t>(across) * static_cast<std::size_t>(down), 0);
    for (int y = 0; y < mask.height; ++y)
        for (int x = 0; x < mask.width; ++x) {
            const bool here = mask.at(x, y);
            const bool mark = outline ? (x + 1 < mask.width && mask.at(x + 1, y) != here) ||
                                            (y + 1 < mask.height && mask.at(x, y + 1) != here)
                                      : here;
            if (mark)
                marked[static_cast<std::size_t>(y / s) * static_cast<std::size_t>(across) +
                       static_cast<std::size_t>(x / s)] = 1;
        }
    std::size_t count = 0;
    for (const std::uint8_t m : marked) count += m;
    return count;
}

/// Minus the least-squares slope of log N(s) against log s over s = minBox, 2 minBox, ...
double dimension(const Mask2D& mask, int minBox, int maxBox, bool outline)
{
    if (minBox < 1 || maxBox < 4 * minBox)
        throw std::invalid_argument(
            "box counting needs three scales: minBox >= 1 and "
            "maxBox >= 4 minBox");
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int n = 0;
    for (int s = minBox; s <= maxBox; s *= 2) {
        const std::size_t boxes = countBoxes(mask, s, outline);
        if (boxes == 0)
            throw std::invalid_argument(outline ? "box counting of a mask without an outline"
                                                : "box counting of an empty mask");
        const double x = std::log(static_cast<double>(s));
        const double y = std::log(static_cast<double>(boxes));
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
        ++n;
    }
    return -(n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace

double boxCountingDimension(const Mask2D& mask, int minBox, int maxBox)
{
    return dimension(mask, minBox, maxBox, false);
}

double outlineDimension(const Mask2D& mask, int minBox, int maxBox)
{
    return dimension(mask, minBox, maxBox, true);
}

}  // namespace cg::algo
