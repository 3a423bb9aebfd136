#pragma once
/// The separate clouds of a mask seen from above: its 4-connected regions of set pixels, each
/// labelled, with its area and perimeter. Plain data; the caller thresholds the optical depth.

#include <cstdint>
#include <vector>

#include "algo/volume/OutlineDimension.h"

namespace cg::algo {

struct Regions {
    int width = 0, height = 0;
    /// Per pixel, row by row: the index of its region, or -1 where the mask is unset.
    std::vector<std::int32_t> label;
    /// Per region, in the order a row-by-row scan first meets them: pixels, and edges between
    /// a set and an unset pixel (the mask's border counts as unset).
    std::vector<double> area, perimeter;

    std::int32_t at(int x, int y) const
    {
        if (x < 0 || y < 0 || x >= width || y >= height) return -1;
        return label[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                     static_cast<std::size_t>(x)];
    }
};

Regions labelRegions(const Mask2D& mask);

}  // namespace cg::algo
