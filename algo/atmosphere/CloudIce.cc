#include "algo/atmosphere/CloudIce.h"

#include <stdexcept>

namespace cg::algo {

void checkGlaciation(const Glaciation& g)
{
    if (!(g.endC < g.startC))
        throw std::invalid_argument(
            "glaciation: the all-ice temperature must be below the "
            "first-ice one");
    if (!(g.retention > 0.0 && g.retention <= 1.0))
        throw std::invalid_argument("glaciation: ice retention must be in (0, 1]");
    if (!(g.effectiveRadius > 0.0 && g.effectiveRadius <= 1e-3))
        throw std::invalid_argument("glaciation: ice effective radius must be in (0, 1 mm]");
}

double iceFraction(double tC, const Glaciation& g)
{
    if (tC >= g.startC) return 0.0;
    if (tC <= g.endC) return 1.0;
    return (g.startC - tC) / (g.startC - g.endC);
}

double extinctionFromIce(double iwcGramsPerM3, double rEff)
{
    if (!(iwcGramsPerM3 > 0.0)) return 0.0;
    return 3.0 * iwcGramsPerM3 * 1e-3 / (2.0 * kIceDensity * rEff);
}

}  // namespace cg::algo
