#pragma once
/// Phase functions for scattering in clouds. Normalisation: a phase function p(cos θ) is a
/// probability density over directions, so ∫ p dω = 1 over the unit sphere (units 1/sr);
/// the isotropic phase function is the constant 1 / (4π).
///
/// θ is the angle between the direction light travels before scattering and the direction
/// it travels after; cos θ = 1 is straight on (forward scattering).

#include <algorithm>
#include <cmath>

namespace cg::algo {

inline constexpr double kInvFourPi = 0.07957747154594767;  // 1 / (4π)

/// Henyey-Greenstein: p(cos θ) = (1 − g²) / (4π (1 + g² − 2 g cos θ)^(3/2)), in 1/sr.
/// g in (−1, 1) is the mean cosine: > 0 forward, 0 isotropic, < 0 backward.
inline double henyeyGreenstein(double cosTheta, double g)
{
    const double gg = g * g;
    const double denom = 1.0 + gg - 2.0 * g * cosTheta;
    return kInvFourPi * (1.0 - gg) / (denom * std::sqrt(denom));
}

/// Two HG lobes blended: (1 − w) HG(g1) + w HG(g2); still integrates to 1 for w in [0, 1].
/// Clouds: a strong forward lobe (g1 ≈ 0.8) and a weak backward one (g2 ≈ −0.3, w ≈ 0.2).
inline double twoLobeHenyeyGreenstein(double cosTheta, double g1, double g2, double w)
{
    const double p1 = henyeyGreenstein(cosTheta, g1);
    return w > 0.0 ? (1.0 - w) * p1 + w * henyeyGreenstein(cosTheta, g2) : p1;
}

/// Two scatterings in a row, the second of light the first turned by any angle: the two-lobe
/// phase function convolved with itself over the sphere. An HG lobe's Legendre moments are
/// g^l, so HG(a) ∗ HG(b) = HG(a b) and the blend gives Σ w_i w_j HG(g_i g_j).
inline double twoLobeHenyeyGreensteinTwice(double cosTheta, double g1, double g2, double w)
{
    return (1.0 - w) * (1.0 - w) * henyeyGreenstein(cosTheta, g1 * g1) +
           2.0 * w * (1.0 - w) * henyeyGreenstein(cosTheta, g1 * g2) +
           w * w * henyeyGreenstein(cosTheta, g2 * g2);
}

/// The δ-Eddington split of the two-lobe phase function (Joseph, Wiscombe and Weinman 1976):
/// a forward peak of weight `peak` treated as no scattering at all, and the rest an HG lobe of
/// asymmetry `g`. The peak is the phase function's second moment, (1 − w) g1² + w g2², so
/// the split keeps its first two moments; the rest's g = (ḡ − peak) / (1 − peak).
struct DeltaEddington {
    double peak = 0.0;
    double g = 0.0;
};

inline DeltaEddington deltaEddington(double g1, double g2, double w)
{
    const double mean = (1.0 - w) * g1 + w * g2;
    DeltaEddington out;
    out.peak = (1.0 - w) * g1 * g1 + w * g2 * g2;
    out.g = out.peak < 1.0 ? (mean - out.peak) / (1.0 - out.peak) : 0.0;
    return out;
}

/// cos θ distributed as Henyey-Greenstein with asymmetry g, from a uniform u in [0, 1)
/// (inverting its cumulative distribution).
inline double sampleHenyeyGreenstein(double g, double u)
{
    if (std::abs(g) < 1e-4) return 1.0 - 2.0 * u;
    const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
    return std::clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
}

/// cos θ distributed as twoLobeHenyeyGreenstein(·, g1, g2, w): lobe 2 when uLobe < w.
inline double sampleTwoLobeHenyeyGreenstein(double g1, double g2, double w, double uLobe,
                                            double u)
{
    return sampleHenyeyGreenstein(uLobe < w ? g2 : g1, u);
}

}  // namespace cg::algo
