#pragma once
/// The size density of a field's clouds, as cloud physics fits it: the number of clouds per
/// unit of size, n(l), in logarithmic bins of the size l = sqrt(area) (Neggers, Jonker and
/// Siebesma 2003), and the exponent b of the power law n(l) ~ l^b fitted by least squares on
/// log n against log l. Shallow cumulus give b about -1.7 in large-eddy simulations and -1.7
/// to -2.5 in satellite studies, up to a scale break near the boundary layer's depth.

#include <cstddef>
#include <vector>

namespace cg::algo {

struct SizeBin {
    double lo = 0, hi = 0;  ///< size range [lo, hi), m
    std::size_t count = 0;  ///< clouds in it
    double density = 0;     ///< count / (hi - lo), clouds per m
};

struct SizeDensityFit {
    std::vector<SizeBin> bins;  ///< from the smallest size up to the largest cloud's bin
    /// The fitted exponent b over the bins holding at least minCount clouds; NaN when fewer
    /// than three such bins.
    double exponent = 0;
    std::size_t fittedBins = 0;
};

/// Bins [smallest r^k, smallest r^(k+1)) for k = 0, 1, ... (r = binRatio); sizes below
/// `smallest` are not counted. Throws std::invalid_argument for smallest <= 0 or binRatio <= 1.
SizeDensityFit fitSizeDensity(const std::vector<double>& sizes, double smallest, double binRatio,
                              std::size_t minCount);

}  // namespace cg::algo
