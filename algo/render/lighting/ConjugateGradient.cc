#include "algo/render/lighting/ConjugateGradient.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <tbb/parallel_for.h>

namespace cg::algo {

namespace {

constexpr std::size_t kBlock = 4096;  ///< rows per parallel task and per partial sum

/// fn(begin, end, block) for every block of rows, in parallel.
template <class Fn>
void forBlocks(std::size_t n, Fn&& fn)
{
    const std::size_t count = (n + kBlock - 1) / kBlock;
    tbb::parallel_for(std::size_t(0), count, [&](std::size_t block) {
        fn(block * kBlock, std::min(n, (block + 1) * kBlock), block);
    });
}

enum Sum { kRz, kRr, kScratch };

/// A column's iterates.
struct Column {
    const std::vector<double>& b;
    std::vector<double>& x;
    // Written before they are read, so left uninitialised: zeroing them would be a pass over
    // memory as long as the solve's first iteration.
    std::unique_ptr<double[]> r, z, p, Ap;
    std::vector<double> partial[3];  ///< per block: r·z, r·r and a scratch sum
    double rz = 0.0, rr = 0.0, bNorm = 0.0;
    double alpha = 0.0, beta = 0.0;  ///< of the current step
    int iterations = 0;

    Column(const std::vector<double>& rhs, std::vector<double>& solution, std::size_t blocks)
        : b(rhs),
          x(solution),
          r(new double[rhs.size()]),
          z(new double[rhs.size()]),
          p(new double[rhs.size()]),
          Ap(new double[rhs.size()])
    {
        for (auto& sums : partial) sums.assign(blocks, 0.0);
    }

    /// Σ of a partial sum's blocks, in order.
    double total(int which) const
    {
        double sum = 0.0;
        for (const double s : partial[which]) sum += s;
        return sum;
    }
};

/// Ap = A v(column) for each column, each matrix row read once for all of them. With
/// `dotWithAp`, also each block's v·Ap into the column's scratch sums.
template <class Vector>
void multiply(const SparseSystem& A, const std::vector<Column*>& columns, Vector&& v,
              bool dotWithAp)
{
    forBlocks(A.size(), [&](std::size_t begin, std::size_t end, std::size_t block) {
        // Column by column over the block: each column's loop is a plain stream, and the
        // block's rows (a few hundred kB) stay in cache for the next column.
        for (Column* c : columns) {
            const double* x = v(*c);
            double* out = c->Ap.get();
            for (std::size_t i = begin; i != end; ++i) {
                const std::int32_t* nb = &A.neighbour[6 * i];
                const float* k = &A.coupling[6 * i];
                double sum = A.diag[i] * x[i];
                for (int f = 0; f < 6; ++f) sum -= k[f] * x[static_cast<std::size_t>(nb[f])];
                out[i] = sum;
            }
            if (!dotWithAp) continue;
            double dot = 0.0;
            for (std::size_t i = begin; i != end; ++i) dot += x[i] * out[i];
            c->partial[kScratch][block] = dot;
        }
    });
}

}  // namespace

int solveConjugateGradient(const SparseSystem& A, const std::vector<SolveColumn>& columns,
                           double tolerance, int maxIterations,
                           const std::function<bool()>& cancelled)
{
    const std::size_t n = A.size();
    const std::size_t blocks = (n + kBlock - 1) / kBlock;
    std::vector<Column> state;
    state.reserve(columns.size());
    for (const SolveColumn& c : columns) state.emplace_back(*c.b, *c.x, blocks);
    std::vector<Column*> active;
    active.reserve(state.size());
    for (Column& c : state) active.push_back(&c);

    // r = b − A x, z = p = r / diag; |b|, r·z and r·r.
    multiply(
        A, active, [](const Column& c) -> const double* { return c.x.data(); }, false);
    for (Column* c : active) {
        forBlocks(n, [&](std::size_t begin, std::size_t end, std::size_t block) {
            double rz = 0.0, rr = 0.0, bb = 0.0;
            for (std::size_t i = begin; i != end; ++i) {
                c->r[i] = c->b[i] - c->Ap[i];
                c->p[i] = c->z[i] = c->r[i] / A.diag[i];
                rz += c->r[i] * c->z[i];
                rr += c->r[i] * c->r[i];
                bb += c->b[i] * c->b[i];
            }
            c->partial[kRz][block] = rz;
            c->partial[kRr][block] = rr;
            c->partial[kScratch][block] = bb;
        });
        c->rz = c->total(kRz);
        c->rr = c->total(kRr);
        c->bNorm = std::sqrt(c->total(kScratch));
    }

    for (int it = 0; it < maxIterations; ++it) {
        // A column with b = 0 has nothing to solve; the others run until they converge.
        std::vector<Column*> next;
        for (Column* c : active)
            if (c->bNorm > 0.0 && std::sqrt(c->rr) > tolerance * c->bNorm) next.push_back(c);
        active.swap(next);
        if (active.empty() || (cancelled && cancelled())) break;

        // Each step is one pass over the rows for every column; the sums are still taken
        // block by block in order, so they do not depend on how the passes are split.
        multiply(
            A, active, [](const Column& c) -> const double* { return c.p.get(); }, true);
        for (Column* c : active) c->alpha = c->rz / c->total(kScratch);
        forBlocks(n, [&](std::size_t begin, std::size_t end, std::size_t block) {
            for (Column* c : active) {
                double rz = 0.0, rr = 0.0;
                for (std::size_t i = begin; i != end; ++i) {
                    c->x[i] += c->alpha * c->p[i];
                    c->r[i] -= c->alpha * c->Ap[i];
                    c->z[i] = c->r[i] / A.diag[i];
                    rz += c->r[i] * c->z[i];
                    rr += c->r[i] * c->r[i];
                }
                c->partial[kRz][block] = rz;
                c->partial[kRr][block] = rr;
            }
        });
        for (Column* c : active) {
            const double rzNext = c->total(kRz);
            c->beta = rzNext / c->rz;
            c->rz = rzNext;
            c->rr = c->total(kRr);
            ++c->iterations;
        }
        forBlocks(n, [&](std::size_t begin, std::size_t end, std::size_t) {
            for (Column* c : active)
                for (std::size_t i = begin; i != end; ++i) c->p[i] = c->z[i] + c->beta * c->p[i];
        });
    }
    int most = 0;
    for (const Column& c : state) most = std::max(most, c.iterations);
    return most;
}

}  // namespace cg::algo
