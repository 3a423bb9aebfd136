#pragma once
/// Jacobi-preconditioned conjugate gradients for the sparse symmetric positive definite
/// systems of RenderDiffusion: one row per cloud cell, coupled to at most its 6 face
/// neighbours. Several right-hand sides of the same matrix are solved together, so each block
/// of matrix rows is read from memory once per iteration for all of them; each column keeps
/// its own step sizes and stops on its own, so its result is what a solve of it alone gives.
/// Sums are taken in fixed blocks, in order: the result does not depend on the thread count.

#include <cstdint>
#include <functional>
#include <vector>

namespace cg::algo {

/// Row i: diag_i x_i − Σ_f coupling_if x_neighbour(i, f).
struct SparseSystem {
    std::vector<double> diag;
    /// 6 per row; a face without a neighbour names the row itself with coupling 0, so the
    /// product needs no branch.
    std::vector<std::int32_t> neighbour;
    std::vector<float> coupling;  ///< 6 per row

    std::size_t size() const { return diag.size(); }
};

/// One right-hand side b and its solution x, solved from x's value on entry.
struct SolveColumn {
    const std::vector<double>* b = nullptr;
    std::vector<double>* x = nullptr;
};

/// Solves A x = b for every column until its residual is at most `tolerance` × |b|, or
/// `maxIterations` pass, or `cancelled` returns true. Returns the most iterations any column
/// took.
int solveConjugateGradient(const SparseSystem& A, const std::vector<SolveColumn>& columns,
                           double tolerance, int maxIterations,
                           const std::function<bool()>& cancelled = {});

}  // namespace cg::algo
