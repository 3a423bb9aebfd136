#include "algo/volume/SizeDensity.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace cg::algo {

namespace {

/// The least-squares slope of y against x over the bins holding at least minCount clouds, in
/// logarithms of the bins' geometric centres and densities.
double logSlope(const std::vector<SizeBin>& bins, std::size_t minCount, std::size_t& used)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
    for (const SizeBin& b : bins) {
        if (b.count < minCount || b.count == 0) continue;
        const double x = 0.5 * (std::log(b.lo) + std::log(b.hi)), y = std::log(b.density);
        sx += x, sy += y, sxx += x * x, sxy += x * y, ++n;
    }
    used = static_cast<std::size_t>(n);
    const double det = n * sxx - sx * sx;
    if (n < 3 || det <= 0) return std::numeric_limits<double>::quiet_NaN();
    return (n * sxy - sx * sy) / det;
}

}  // namespace

SizeDensityFit fitSizeDensity(const std::vector<double>& sizes, double smallest, double binRatio,
                              std::size_t minCount)
{
    if (!(smallest > 0)) throw std::invalid_argument("fitSizeDensity: smallest size must be > 0");
    if (!(binRatio > 1)) throw std::invalid_argument("fitSizeDensity: bin ratio must be > 1");
    SizeDensityFit fit;
    const double logRatio = std::log(binRatio);
    for (const double l : sizes) {
        if (!(l >= smallest) || !std::isfinite(l)) continue;
        const auto k = static_cast<std::size_t>(std::floor(std::log(l / smallest) / logRatio));
        while (fit.bins.size() <= k) {
            SizeBin b;
            b.lo = smallest * std::pow(binRatio, static_cast<double>(fit.bins.size()));
            b.hi = b.lo * binRatio;
            fit.bins.push_back(b);
        }
        ++fit.bins[k].count;
    }
    for (SizeBin& b : fit.bins) b.density = static_cast<double>(b.count) / (b.hi - b.lo);
    fit.exponent = logSlope(fit.bins, minCount, fit.fittedBins);
    return fit;
}

}  // namespace cg::algo
