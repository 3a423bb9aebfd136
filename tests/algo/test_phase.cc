// Phase.h: the helpers the fast renderer builds its model on, against numerical integrals
// over the sphere.

#include <cmath>

#include <gtest/gtest.h>

#include "algo/render/Phase.h"

namespace cg {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kG1 = 0.8, kG2 = -0.3, kBlend = 0.2;  // the Renderer's defaults

double twoLobe(double mu) { return algo::twoLobeHenyeyGreenstein(mu, kG1, kG2, kBlend); }

/// ∫ p(μ) P_l(μ) dω over the sphere for l = 0, 1, 2 (midpoint rule in μ).
void legendreMoments(double (*p)(double), double out[3])
{
    const int n = 200000;
    out[0] = out[1] = out[2] = 0.0;
    for (int i = 0; i < n; ++i) {
        const double mu = -1.0 + (i + 0.5) * 2.0 / n;
        const double w = p(mu) * 2.0 * kPi * (2.0 / n);
        out[0] += w;
        out[1] += w * mu;
        out[2] += w * 0.5 * (3.0 * mu * mu - 1.0);
    }
}

TEST(Phase, TwoLobeMomentsAreTheBlendOfTheLobesPowers)
{
    // An HG lobe's l-th Legendre moment is g^l.
    double m[3];
    legendreMoments(twoLobe, m);
    EXPECT_NEAR(m[0], 1.0, 1e-6);
    EXPECT_NEAR(m[1], (1 - kBlend) * kG1 + kBlend * kG2, 1e-6);
    EXPECT_NEAR(m[2], (1 - kBlend) * kG1 * kG1 + kBlend * kG2 * kG2, 1e-6);
}

TEST(Phase, DeltaEddingtonPeakIsTheSecondMomentAndTheSplitKeepsTheFirst)
{
    double m[3];
    legendreMoments(twoLobe, m);
    const algo::DeltaEddington split = algo::deltaEddington(kG1, kG2, kBlend);
    EXPECT_NEAR(split.peak, m[2], 1e-6);
    // f δ + (1 − f) HG(g'): the peak's mean cosine is 1, the rest's g'.
    EXPECT_NEAR(split.peak + (1.0 - split.peak) * split.g, m[1], 1e-6);
    EXPECT_GT(split.g, 0.0);
    EXPECT_LT(split.g, m[1]);
    // An isotropic phase function has no peak.
    const algo::DeltaEddington none = algo::deltaEddington(0.0, 0.0, 0.0);
    EXPECT_EQ(none.peak, 0.0);
    EXPECT_EQ(none.g, 0.0);
}

TEST(Phase, TwiceIsThePhaseFunctionConvolvedWithItself)
{
    // p2(ω_in·ω_out) = ∫ p(ω_in·ω) p(ω·ω_out) dω, with ω_in = z and ω_out in the xz plane.
    const int nMu = 4000, nPhi = 720;
    for (const double cosOut : {-0.9, -0.3, 0.2, 0.7, 0.95}) {
        const double sinOut = std::sqrt(1.0 - cosOut * cosOut);
        double sum = 0.0;
        for (int i = 0; i < nMu; ++i) {
            const double mu = -1.0 + (i + 0.5) * 2.0 / nMu;
            const double s = std::sqrt(1.0 - mu * mu);
            const double first = twoLobe(mu);
            for (int j = 0; j < nPhi; ++j) {
                const double phi = (j + 0.5) * 2.0 * kPi / nPhi;
                const double cosSecond = s * std::cos(phi) * sinOut + mu * cosOut;
                sum += first * twoLobe(cosSecond);
            }
        }
        sum *= (2.0 / nMu) * (2.0 * kPi / nPhi);
        const double closed = algo::twoLobeHenyeyGreensteinTwice(cosOut, kG1, kG2, kBlend);
        EXPECT_NEAR(sum, closed, 2e-4 * closed + 1e-6) << "cos θ = " << cosOut;
    }
}

TEST(Phase, SampledCosinesHaveTheLobesMean)
{
    // Stratified u: the mean of the sampled cos θ is the lobe's g.
    for (const double g : {-0.3, 0.0, 0.5, 0.8}) {
        const int n = 100000;
        double sum = 0.0;
        for (int i = 0; i < n; ++i) sum += algo::sampleHenyeyGreenstein(g, (i + 0.5) / n);
        EXPECT_NEAR(sum / n, g, 1e-4) << "g = " << g;
    }
}

}  // namespace
}  // namespace cg
