// solveConjugateGradient (algo/render/lighting/ConjugateGradient.h): the solution of a known
// system, columns solved together equal to each solved alone, and the same bits for any thread
// count.

#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "algo/render/lighting/ConjugateGradient.h"

namespace cg {
namespace {

using algo::SolveColumn;
using algo::SparseSystem;

constexpr int kSide = 20;  // 8000 rows: two partial-sum blocks

/// A diffusion-like system on a kSide³ lattice: random face couplings, each row's diagonal
/// their sum plus a little absorption (symmetric, diagonally dominant, positive definite).
SparseSystem lattice()
{
    const auto at = [](int i, int j, int k) { return (i * kSide + j) * kSide + k; };
    const std::size_t n = std::size_t(kSide) * kSide * kSide;
    SparseSystem A;
    A.diag.assign(n, 0.01);
    A.neighbour.resize(6 * n);
    A.coupling.assign(6 * n, 0.0f);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.2f, 2.0f);
    for (int i = 0; i < kSide; ++i)
        for (int j = 0; j < kSide; ++j)
            for (int k = 0; k < kSide; ++k) {
                const int row = at(i, j, k);
                for (int f = 0; f < 6; ++f) A.neighbour[6 * row + f] = row;
            }
    // Each face's coupling drawn once and set on both rows it joins.
    for (int i = 0; i < kSide; ++i)
        for (int j = 0; j < kSide; ++j)
            for (int k = 0; k < kSide; ++k)
                for (int axis = 0; axis < 3; ++axis) {
                    int nb[3] = {i, j, k};
                    if (++nb[axis] >= kSide) continue;
                    const int row = at(i, j, k), other = at(nb[0], nb[1], nb[2]);
                    const float c = u(rng);
                    A.neighbour[6 * row + 2 * axis + 1] = other;
                    A.coupling[6 * row + 2 * axis + 1] = c;
                    A.neighbour[6 * other + 2 * axis] = row;
                    A.coupling[6 * other + 2 * axis] = c;
                    A.diag[static_cast<std::size_t>(row)] += c;
                    A.diag[static_cast<std::size_t>(other)] += c;
                }
    return A;
}

std::vector<double> times(const SparseSystem& A, const std::vector<double>& x)
{
    std::vector<double> y(A.size());
    for (std::size_t i = 0; i < A.size(); ++i) {
        y[i] = A.diag[i] * x[i];
        for (int f = 0; f < 6; ++f)
            y[i] -= A.coupling[6 * i + f] * x[static_cast<std::size_t>(A.neighbour[6 * i + f])];
    }
    return y;
}

std::vector<double> randomVector(std::size_t n, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<double> v(n);
    for (double& x : v) x = u(rng);
    return v;
}

TEST(ConjugateGradient, FindsTheSolutionOfAKnownSystem)
{
    const SparseSystem A = lattice();
    const std::vector<double> truth = randomVector(A.size(), 1);
    const std::vector<double> b = times(A, truth);
    std::vector<double> x(A.size(), 0.0);
    const int iterations = algo::solveConjugateGradient(A, {{&b, &x}}, 1e-10, 1000);
    EXPECT_GT(iterations, 1);
    EXPECT_LT(iterations, 1000);
    double worst = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) worst = std::max(worst, std::abs(x[i] - truth[i]));
    EXPECT_LT(worst, 1e-6);
}

TEST(ConjugateGradient, ColumnsSolvedTogetherEqualEachSolvedAlone)
{
    const SparseSystem A = lattice();
    const std::vector<double> b1 = randomVector(A.size(), 2), b2 = randomVector(A.size(), 3);
    const std::vector<double> zero(A.size(), 0.0);
    std::vector<double> alone1(A.size(), 0.0), alone2(A.size(), 0.0);
    const int it1 = algo::solveConjugateGradient(A, {{&b1, &alone1}}, 1e-6, 1000);
    const int it2 = algo::solveConjugateGradient(A, {{&b2, &alone2}}, 1e-6, 1000);
    std::vector<double> together1(A.size(), 0.0), together2(A.size(), 0.0),
        untouched(A.size(), 0.5);
    const int both = algo::solveConjugateGradient(
        A, {{&b1, &together1}, {&zero, &untouched}, {&b2, &together2}}, 1e-6, 1000);
    EXPECT_EQ(both, std::max(it1, it2));
    EXPECT_EQ(together1, alone1);
    EXPECT_EQ(together2, alone2);
    EXPECT_EQ(untouched, std::vector<double>(A.size(), 0.5));  // b = 0: nothing to solve
}

TEST(ConjugateGradient, SameBitsForAnyThreadCount)
{
    const SparseSystem A = lattice();
    const std::vector<double> b = randomVector(A.size(), 4);
    std::vector<double> result[2];
    for (int threads : {1, 2}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        result[threads - 1].assign(A.size(), 0.0);
        algo::solveConjugateGradient(A, {{&b, &result[threads - 1]}}, 1e-8, 1000);
    }
    EXPECT_EQ(result[0], result[1]);
}

}  // namespace
}  // namespace cg
