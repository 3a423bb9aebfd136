// Phase.h: the phase functions and the helpers the fast renderer builds its model on, against
// numerical integrals over the sphere.

#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "algo/render/media/Phase.h"

namespace cg {
namespace {

using algo::PhaseFunction;
using algo::PhaseLobe;

constexpr double kPi = 3.14159265358979323846;
constexpr double kG1 = 0.8, kG2 = -0.3, kBlend = 0.2;  // the Renderer's defaults

/// ∫ p(μ) P_l(μ) dω over the sphere for l = 0, 1, 2, in θ = π t² with t uniform (midpoint
/// rule): the points crowd toward θ = 0, where Mie's forward lobe is a fraction of a degree.
void legendreMoments(const PhaseFunction& p, double out[3])
{
    const int n = 400000;
    out[0] = out[1] = out[2] = 0.0;
    for (int i = 0; i < n; ++i) {
        const double t = (i + 0.5) / n;
        const double theta = kPi * t * t, mu = std::cos(theta);
        const double w = p(mu) * 2.0 * kPi * std::sin(theta) * (2.0 * kPi * t / n);
        out[0] += w;
        out[1] += w * mu;
        out[2] += w * 0.5 * (3.0 * mu * mu - 1.0);
    }
}

struct Case {
    std::string name;
    PhaseFunction phase;
};

class PhaseModels : public ::testing::TestWithParam<Case> {};

TEST_P(PhaseModels, IntegratesToOneAndHasItsClosedFormMoments)
{
    const PhaseFunction& p = GetParam().phase;
    double m[3];
    legendreMoments(p, m);
    EXPECT_NEAR(m[0], 1.0, 1e-5);
    EXPECT_NEAR(m[1], p.moment(1), 1e-5);
    EXPECT_NEAR(m[2], p.moment(2), 1e-5);
}

TEST_P(PhaseModels, DeltaEddingtonPeakIsTheSecondMomentAndTheSplitKeepsTheFirst)
{
    const PhaseFunction& p = GetParam().phase;
    double m[3];
    legendreMoments(p, m);
    const algo::DeltaEddington split = p.deltaEddington();
    EXPECT_NEAR(split.peak, m[2], 1e-5);
    // f δ + (1 − f) HG(g'): the peak's mean cosine is 1, the rest's g'.
    EXPECT_NEAR(split.peak + (1.0 - split.peak) * split.g, m[1], 1e-5);
    EXPECT_GT(split.g, 0.0);
    EXPECT_LT(split.g, m[1]);
}

TEST_P(PhaseModels, SampledCosinesHaveTheFirstTwoMoments)
{
    const PhaseFunction& p = GetParam().phase;
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const int n = 400000;
    double s1 = 0.0, s2 = 0.0, q1 = 0.0, q2 = 0.0;
    for (int i = 0; i < n; ++i) {
        const double mu = p.sample([&] { return u(rng); });
        const double p2 = 0.5 * (3.0 * mu * mu - 1.0);
        s1 += mu;
        q1 += mu * mu;
        s2 += p2;
        q2 += p2 * p2;
    }
    const auto within = [&](double sum, double squares, double expected) {
        const double mean = sum / n, se = std::sqrt((squares / n - mean * mean) / n);
        EXPECT_LT(std::abs(mean - expected), 4.0 * se) << mean << " vs " << expected;
    };
    within(s1, q1, p.moment(1));
    within(s2, q2, p.moment(2));
}

TEST_P(PhaseModels, TwiceIsADensity)
{
    // Light scattered twice goes somewhere: ∫ p∗p dω = 1, the table's series truncated and
    // interpolated included.
    const algo::PhaseTwice twice(GetParam().phase);
    const int n = 400000;
    double total = 0.0;
    for (int i = 0; i < n; ++i) {
        const double t = (i + 0.5) / n, theta = kPi * t * t;
        total += twice(std::cos(theta)) * 2.0 * kPi * std::sin(theta) * (2.0 * kPi * t / n);
    }
    EXPECT_NEAR(total, 1.0, 2e-3);
}

INSTANTIATE_TEST_SUITE_P(
    Phase, PhaseModels,
    ::testing::Values(Case{"twoLobeHG", PhaseFunction::twoLobeHenyeyGreenstein(kG1, kG2, kBlend)},
                      Case{"mie5um", PhaseFunction::mie(5.0)},
                      Case{"mie20um", PhaseFunction::mie(20.0)},
                      Case{"mie50um", PhaseFunction::mie(50.0)},
                      Case{"draine",
                           PhaseFunction(PhaseLobe{0.7, 0.5, 5.0}, PhaseLobe{0.3, -0.2, 0.0})}),
    [](const ::testing::TestParamInfo<Case>& param) { return param.param.name; });

TEST(Phase, TwoLobeMomentsAreTheBlendOfTheLobesPowers)
{
    // An HG lobe's l-th Legendre moment is g^l.
    const PhaseFunction p = PhaseFunction::twoLobeHenyeyGreenstein(kG1, kG2, kBlend);
    EXPECT_DOUBLE_EQ(p.moment(1), (1 - kBlend) * kG1 + kBlend * kG2);
    EXPECT_DOUBLE_EQ(p.moment(2), (1 - kBlend) * kG1 * kG1 + kBlend * kG2 * kG2);
    const algo::DeltaEddington none = PhaseFunction().deltaEddington();
    EXPECT_EQ(none.peak, 0.0);  // isotropic: no peak
    EXPECT_EQ(none.g, 0.0);
}

TEST(Phase, TwiceIsThePhaseFunctionConvolvedWithItself)
{
    // Closed form for HG lobes, HG(a) ∗ HG(b) = HG(a b); a brute-force convolution,
    // p2(ω_in·ω_out) = ∫ p(ω_in·ω) p(ω·ω_out) dω, for a Draine lobe.
    const PhaseFunction hg = PhaseFunction::twoLobeHenyeyGreenstein(kG1, kG2, kBlend);
    const algo::PhaseTwice hgTwice(hg);
    const PhaseFunction draine(PhaseLobe{0.7, 0.5, 5.0}, PhaseLobe{0.3, -0.2, 0.0});
    const algo::PhaseTwice draineTwice(draine);
    const int nMu = 4000, nPhi = 720;
    for (const double cosOut : {-0.9, -0.3, 0.2, 0.7, 0.95}) {
        const double w = kBlend;
        const double closed = (1 - w) * (1 - w) * algo::henyeyGreenstein(cosOut, kG1 * kG1) +
                              2 * w * (1 - w) * algo::henyeyGreenstein(cosOut, kG1 * kG2) +
                              w * w * algo::henyeyGreenstein(cosOut, kG2 * kG2);
        EXPECT_NEAR(hgTwice(cosOut), closed, 1e-4 * closed) << "cos θ = " << cosOut;

        const double sinOut = std::sqrt(1.0 - cosOut * cosOut);
        double sum = 0.0;
        for (int i = 0; i < nMu; ++i) {
            const double mu = -1.0 + (i + 0.5) * 2.0 / nMu;
            const double s = std::sqrt(1.0 - mu * mu);
            const double first = draine(mu);
            for (int j = 0; j < nPhi; ++j) {
                const double phi = (j + 0.5) * 2.0 * kPi / nPhi;
                sum += first * draine(s * std::cos(phi) * sinOut + mu * cosOut);
            }
        }
        sum *= (2.0 / nMu) * (2.0 * kPi / nPhi);
        EXPECT_NEAR(draineTwice(cosOut), sum, 2e-4 * sum + 1e-6) << "cos θ = " << cosOut;
    }
}

TEST(Phase, MieFitHasCloudDropletsMeanCosineAndAGlory)
{
    // Water droplets of 5-50 μm scatter visible light with a mean cosine of about 0.85-0.9,
    // far more sharply forward than the two-lobe default, and back toward the sun (the glory)
    // more than to the side.
    const PhaseFunction twoLobe = PhaseFunction::twoLobeHenyeyGreenstein(kG1, kG2, kBlend);
    for (const double d : {5.0, 10.0, 20.0, 50.0}) {
        const PhaseFunction mie = PhaseFunction::mie(d);
        EXPECT_GT(mie.meanCosine(), 0.84) << d;
        EXPECT_LT(mie.meanCosine(), 0.90) << d;
        EXPECT_GT(mie(1.0), 20.0 * twoLobe(1.0)) << d;
        EXPECT_GT(mie(-1.0), 3.0 * mie(std::cos(100.0 * kPi / 180.0))) << d;
    }
    // Larger droplets, a sharper forward lobe.
    EXPECT_GT(PhaseFunction::mie(50.0)(1.0), PhaseFunction::mie(10.0)(1.0));
}

}  // namespace
}  // namespace cg
