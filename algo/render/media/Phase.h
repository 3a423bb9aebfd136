#pragma once
/// Phase functions for scattering in clouds. Normalisation: a phase function p(cos θ) is a
/// probability density over directions, so ∫ p dω = 1 over the unit sphere (units 1/sr);
/// the isotropic phase function is the constant 1 / (4π).
///
/// θ is the angle between the direction light travels before scattering and the direction
/// it travels after; cos θ = 1 is straight on (forward scattering).

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "algo/render/RenderSettings.h"

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

/// cos θ distributed as Henyey-Greenstein with asymmetry g, from a uniform u in [0, 1)
/// (inverting its cumulative distribution).
inline double sampleHenyeyGreenstein(double g, double u)
{
    if (std::abs(g) < 1e-4) return 1.0 - 2.0 * u;
    const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
    return std::clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
}

/// Draine's (2003) lobe: HG(g) (1 + α cos²θ) / (1 + α (1 + 2 g²) / 3), normalised; α = 0 is
/// Henyey-Greenstein, α > 0 lifts the forward and backward directions against the side.
struct PhaseLobe {
    double weight = 1.0;
    double g = 0.0;
    double alpha = 0.0;

    double operator()(double cosTheta) const
    {
        const double p = henyeyGreenstein(cosTheta, g);
        if (alpha == 0.0) return p;
        return p * (1.0 + alpha * cosTheta * cosTheta) / (1.0 + alpha * (1.0 + 2.0 * g * g) / 3.0);
    }

    /// The Legendre moment χ_l = ∫ p P_l dω: g^l for HG; for Draine, μ² P_l expanded in
    /// P_{l−2}, P_l, P_{l+2} against HG's moments.
    double moment(int l) const;
};

/// The δ-Eddington split of a phase function (Joseph, Wiscombe and Weinman 1976): a forward
/// peak of weight `peak` treated as no scattering at all, and the rest a lobe of asymmetry
/// `g`. The peak is the phase function's second moment χ_2, so the split keeps its first two
/// moments; the rest's g = (χ_1 − peak) / (1 − peak).
struct DeltaEddington {
    double peak = 0.0;
    double g = 0.0;
};

/// A blend of two lobes, each Henyey-Greenstein or Draine.
///   - twoLobeHenyeyGreenstein(g1, g2, w): (1 − w) HG(g1) + w HG(g2); clouds: a strong
///     forward lobe (g1 ≈ 0.8) and a weak backward one (g2 ≈ −0.3, w ≈ 0.2).
///   - mie(d): Jendersie and d'Eon's (2023) fit to Mie scattering by water droplets of
///     diameter d (5 to 50 μm): (1 − w_D) HG(g_HG) + w_D Draine(g_D, α), with their fitted
///     functions of d. Its sharp forward lobe (g_HG ≈ 0.99) is the silver lining, Draine's
///     α lobe the fog bow and glory side of the curve.
class PhaseFunction {
public:
    PhaseFunction() = default;  ///< isotropic
    /// weights summing to 1
    PhaseFunction(const PhaseLobe& first, const PhaseLobe& second) : mLobes{first, second} {}
    static PhaseFunction twoLobeHenyeyGreenstein(double g1, double g2, double w);
    static PhaseFunction mie(double dropletDiameterMicrons);

    double operator()(double cosTheta) const
    {
        const double p = mLobes[0](cosTheta);
        return mLobes[1].weight > 0.0
                   ? mLobes[0].weight * p + mLobes[1].weight * mLobes[1](cosTheta)
                   : p;
    }

    double moment(int l) const
    {
        return mLobes[0].weight * mLobes[0].moment(l) + mLobes[1].weight * mLobes[1].moment(l);
    }
    double meanCosine() const { return moment(1); }

    /// Each lobe's g times k, its α kept: the renderer's phase functions of light that is
    /// already partly diffuse (k = |F| / φ) or of a multiple-scattering octave.
    PhaseFunction narrowed(double k) const
    {
        PhaseFunction out = *this;
        for (PhaseLobe& lobe : out.mLobes) lobe.g *= k;
        return out;
    }

    DeltaEddington deltaEddington() const
    {
        DeltaEddington out;
        out.peak = moment(2);
        out.g = out.peak < 1.0 ? (moment(1) - out.peak) / (1.0 - out.peak) : 0.0;
        return out;
    }

    /// cos θ drawn from the phase function; `uniform()` returns uniforms in [0, 1). Draws a
    /// lobe, then HG(g), which a Draine lobe accepts with probability (1 + α cos²θ)/(1 + α).
    template <class Uniform>
    double sample(Uniform&& uniform) const
    {
        const double uLobe = uniform();
        const PhaseLobe& lobe = uLobe < mLobes[1].weight ? mLobes[1] : mLobes[0];
        for (;;) {
            const double cosTheta = sampleHenyeyGreenstein(lobe.g, uniform());
            if (lobe.alpha == 0.0 ||
                uniform() * (1.0 + lobe.alpha) < 1.0 + lobe.alpha * cosTheta * cosTheta)
                return cosTheta;
        }
    }

    const std::array<PhaseLobe, 2>& lobes() const { return mLobes; }

private:
    std::array<PhaseLobe, 2> mLobes{PhaseLobe{1.0, 0.0, 0.0}, PhaseLobe{0.0, 0.0, 0.0}};
};

/// The medium's phase function.
PhaseFunction phaseOf(const RenderMedium& medium);

/// Two scatterings in a row, the second of light the first turned by any angle: the phase
/// function convolved with itself over the sphere, p∗p = Σ_l (2l + 1) / (4π) χ_l² P_l(cos θ)
/// (convolution multiplies Legendre moments). Tabulated once in θ (the series runs until
/// χ_l² is negligible: thousands of terms for Mie's sharp forward lobe) and interpolated.
class PhaseTwice {
public:
    explicit PhaseTwice(const PhaseFunction& phase);
    double operator()(double cosTheta) const;

private:
    std::vector<double> mTable;  ///< at θ_i = i π / (size − 1)
};

}  // namespace cg::algo
