#pragma once
/// The fractal dimension of a cloud's outline, as cloud physics measures it (Lovejoy 1982
/// found 1.35 for cloud perimeters; a smooth curve is 1): the outline of a 2D mask (a
/// silhouette thresholded on optical depth, or a field seen from above), and its box-counting
/// dimension. Plain data: the caller projects the volume and thresholds it.

#include <cstdint>
#include <vector>

namespace cg::algo {

/// A width x height grid of set (1) and unset (0) pixels, row by row.
struct Mask2D {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> set;

    bool at(int x, int y) const
    {
        return x >= 0 && y >= 0 && x < width && y < height &&
               set[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                   static_cast<std::size_t>(x)] != 0;
    }
};

/// The box-counting dimension of the set pixels of `mask`: N(s), the number of s x s boxes of
/// a grid anchored at (0, 0) that hold a set pixel, for s = minBox, 2 minBox, ... up to
/// maxBox; minus the least-squares slope of log N against log s. Throws std::invalid_argument
/// for fewer than three scales (minBox < 1, or maxBox < 4 minBox) or an empty mask.
double boxCountingDimension(const Mask2D& mask, int minBox, int maxBox);

/// The box-counting dimension of the outline of the region `mask` sets: N(s) counts the boxes
/// that hold an edge between a set and an unset pixel (each edge in one box, however the
/// region lies against the boxes). Pixels stair-step along a slanted edge, which reads as
/// detail at boxes of a few pixels: start at minBox 4 or more. The grid's edge is not an
/// outline: keep the region inside it. Same scales and refusals as boxCountingDimension, and a mask
/// whose region has no outline (all set or all unset) is refused.
double outlineDimension(const Mask2D& mask, int minBox, int maxBox);

}  // namespace cg::algo
