#pragma once
/// What a meteorologist reads off a cloud: its base, its top and its cloud fraction
/// by height, from the condensation particles of one frame.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace cg::algo {

struct CloudColumn {
    std::size_t condensed = 0;
    double baseM = std::numeric_limits<double>::quiet_NaN();  ///< lowest condensed particle
    double topM = std::numeric_limits<double>::quiet_NaN();   ///< highest condensed particle
    double binM = 0.0;                                        ///< height of one fraction bin
    /// Per bin k, heights [k binM, (k + 1) binM): the fraction of the ground's cells (of the
    /// bounding box of all particles, vapour too) above which a condensed particle lies in
    /// that bin. Bins run from the ground to the top.
    std::vector<double> fraction;
};

/// Heights above the ground; `condensedFrame[i] >= 0` marks a condensation particle. Ground
/// cells are `cellM` wide, coarsened when the particles span more than 4 million of them.
CloudColumn cloudColumn(const float* x, const float* y, const float* z,
                        const std::int32_t* condensedFrame, std::size_t n, double binM,
                        double cellM);

}  // namespace cg::algo
