#include "algo/render/media/Phase.h"

#include <tbb/parallel_for.h>

namespace cg::algo {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr std::size_t kTwiceTable = 4097;  ///< θ samples of PhaseTwice
constexpr int kMostTerms = 20000;          ///< of its Legendre series
constexpr double kNegligible = 1e-13;      ///< (2l + 1) χ_l² below this ends the series

/// χ_l of HG(g): g^l (0 for l < 0).
double hgMoment(double g, int l) { return l < 0 ? 0.0 : std::pow(g, l); }

}  // namespace

double PhaseLobe::moment(int l) const
{
    if (alpha == 0.0) return hgMoment(g, l);
    // μ² P_l = a P_{l+2} + b P_l + c P_{l−2} (from μ P_l = ((l+1) P_{l+1} + l P_{l−1}) / (2l+1)).
    const double L = l;
    const double a = (L + 1.0) * (L + 2.0) / ((2.0 * L + 1.0) * (2.0 * L + 3.0));
    const double b = (2.0 * L * L + 2.0 * L - 1.0) / ((2.0 * L - 1.0) * (2.0 * L + 3.0));
    const double c = L * (L - 1.0) / ((2.0 * L - 1.0) * (2.0 * L + 1.0));
    const double muSquared = a * hgMoment(g, l + 2) + b * hgMoment(g, l) + c * hgMoment(g, l - 2);
    return (hgMoment(g, l) + alpha * muSquared) / (1.0 + alpha * (1.0 + 2.0 * g * g) / 3.0);
}

PhaseFunction PhaseFunction::twoLobeHenyeyGreenstein(double g1, double g2, double w)
{
    return {PhaseLobe{1.0 - w, g1, 0.0}, PhaseLobe{w, g2, 0.0}};
}

PhaseFunction PhaseFunction::mie(double d)
{
    // Jendersie and d'Eon (2023), "An Approximate Mie Scattering Function for Fog and Cloud
    // Rendering": their fits for 5 μm ≤ d ≤ 50 μm.
    const double gHG = std::exp(-0.0990567 / (d - 1.67154));
    const double gD = std::exp(-2.20679 / (d + 3.91029) - 0.428934);
    const double alpha = std::exp(3.62489 - 8.29288 / (d + 5.52825));
    const double wD = std::exp(-0.599085 / (d - 0.641583) - 0.665888);
    return {PhaseLobe{1.0 - wD, gHG, 0.0}, PhaseLobe{wD, gD, alpha}};
}

PhaseFunction phaseOf(const RenderMedium& medium)
{
    return medium.phase == PhaseModel::Mie
               ? PhaseFunction::mie(medium.dropletDiameter)
               : PhaseFunction::twoLobeHenyeyGreenstein(medium.g, medium.g2, medium.lobeBlend);
}

PhaseTwice::PhaseTwice(const PhaseFunction& phase)
{
    std::vector<double> weight;  // (2l + 1) / (4π) χ_l²
    for (int l = 0; l < kMostTerms; ++l) {
        const double chi = phase.moment(l);
        const double w = (2.0 * l + 1.0) * chi * chi;
        if (l > 2 && w < kNegligible) break;
        weight.push_back(w * kInvFourPi);
    }
    mTable.assign(kTwiceTable, 0.0);
    tbb::parallel_for(std::size_t(0), kTwiceTable, [&](std::size_t i) {
        const double mu = std::cos(kPi * static_cast<double>(i) / (kTwiceTable - 1));
        double previous = 1.0, current = mu;  // P_0, P_1
        double sum = weight[0] + (weight.size() > 1 ? weight[1] * mu : 0.0);
        for (std::size_t l = 2; l < weight.size(); ++l) {
            const double L = static_cast<double>(l);
            const double next = ((2.0 * L - 1.0) * mu * current - (L - 1.0) * previous) / L;
            previous = current;
            current = next;
            sum += weight[l] * current;
        }
        mTable[i] = std::max(0.0, sum);
    });
}

double PhaseTwice::operator()(double cosTheta) const
{
    const double x = std::acos(std::clamp(cosTheta, -1.0, 1.0)) / kPi * (kTwiceTable - 1);
    const auto i = std::min(static_cast<std::size_t>(x), kTwiceTable - 2);
    const double f = x - static_cast<double>(i);
    return (1.0 - f) * mTable[i] + f * mTable[i + 1];
}

}  // namespace cg::algo
