#include "algo/render/RenderDiffusion.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace cg::algo {

namespace {

constexpr std::size_t kMaxCells = std::size_t(1) << 21;
constexpr int kMaxIterations = 400;
constexpr double kTolerance = 1e-4;  ///< relative residual at which the solve stops
constexpr std::size_t kSumBlock = 4096;

/// The sparse symmetric system over the cloud's cells: row i is
/// diag_i φ_i − Σ_f k_if φ_nb(f) for its neighbours inside the cloud.
struct System {
    std::vector<double> diag;
    std::vector<std::int32_t> neighbour;  ///< 6 per cell, −1 outside the cloud
    std::vector<float> coupling;          ///< 6 per cell, k_if

    std::size_t size() const { return diag.size(); }

    void multiply(const std::vector<double>& x, std::vector<double>& y) const
    {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, size(), 2048),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                              for (std::size_t i = r.begin(); i != r.end(); ++i) {
                                  double v = diag[i] * x[i];
                                  for (int f = 0; f < 6; ++f) {
                                      const std::int32_t j = neighbour[6 * i + f];
                                      if (j >= 0) v -= coupling[6 * i + f] * x[j];
                                  }
                                  y[i] = v;
                              }
                          });
    }
};

/// Σ a_i b_i in fixed blocks, summed in order: the same bits for any thread count.
double dot(const std::vector<double>& a, const std::vector<double>& b)
{
    const std::size_t blocks = (a.size() + kSumBlock - 1) / kSumBlock;
    std::vector<double> partial(blocks, 0.0);
    tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t blk) {
        double s = 0.0;
        const std::size_t end = std::min(a.size(), (blk + 1) * kSumBlock);
        for (std::size_t i = blk * kSumBlock; i < end; ++i) s += a[i] * b[i];
        partial[blk] = s;
    });
    double sum = 0.0;
    for (const double s : partial) sum += s;
    return sum;
}

/// Jacobi-preconditioned conjugate gradients from x; returns the iterations taken.
int solve(const System& A, const std::vector<double>& b, std::vector<double>& x,
          const std::function<bool()>& cancelled)
{
    const std::size_t n = A.size();
    std::vector<double> r(n), z(n), p(n), Ap(n);
    A.multiply(x, Ap);
    for (std::size_t i = 0; i < n; ++i) r[i] = b[i] - Ap[i];
    const double bNorm = std::sqrt(dot(b, b));
    if (!(bNorm > 0.0)) return 0;
    for (std::size_t i = 0; i < n; ++i) p[i] = z[i] = r[i] / A.diag[i];
    double rz = dot(r, z);
    int it = 0;
    for (; it < kMaxIterations; ++it) {
        if (std::sqrt(dot(r, r)) <= kTolerance * bNorm) break;
        if (cancelled && cancelled()) break;
        A.multiply(p, Ap);
        const double alpha = rz / dot(p, Ap);
        for (std::size_t i = 0; i < n; ++i) {
            x[i] += alpha * p[i];
            r[i] -= alpha * Ap[i];
            z[i] = r[i] / A.diag[i];
        }
        const double rzNext = dot(r, z);
        const double beta = rzNext / rz;
        rz = rzNext;
        for (std::size_t i = 0; i < n; ++i) p[i] = z[i] + beta * p[i];
    }
    return it;
}

}  // namespace

RenderDiffusion::RenderDiffusion(const openvdb::FloatGrid& grid, const RenderLightMap& sunMap,
                                 const RenderMedium& medium, int cellVoxels,
                                 const std::function<bool()>& cancelled)
    : mXform(grid.transform())
{
    const openvdb::CoordBBox active = grid.evalActiveVoxelBoundingBox();
    if (active.empty() || !(medium.extinction > 0.0)) return;

    // Cells of c^3 voxels with one empty cell around the cloud, c grown until they fit.
    const openvdb::Coord dim = active.dim();
    const auto cellsFor = [&](int c) {
        std::size_t n = 1;
        for (int a = 0; a < 3; ++a) n *= static_cast<std::size_t>((dim[a] + c - 1) / c + 2);
        return n;
    };
    mVoxels = std::max(1, cellVoxels);
    while (cellsFor(mVoxels) > kMaxCells) ++mVoxels;
    const int c = mVoxels;
    for (int a = 0; a < 3; ++a) mN[a] = (dim[a] + c - 1) / c + 2;
    mFirstVoxel = active.min() - openvdb::Coord(c);
    const openvdb::Vec3d voxel = grid.voxelSize();
    const double h[3] = {voxel.x() * c, voxel.y() * c, voxel.z() * c};
    mH = std::min({h[0], h[1], h[2]});
    const std::size_t dense = static_cast<std::size_t>(mN[0]) * static_cast<std::size_t>(mN[1]) *
                              static_cast<std::size_t>(mN[2]);

    // Mean extinction of each cell's voxels, and the mean rate at which they scatter sun
    // light for the first time, σ_s exp(−τ_sun), taken voxel by voxel: exp(−τ) varies
    // across a cell by far more than linearly where the sun enters the cloud.
    std::vector<double> sigmaT(dense, 0.0), scatterOnce(dense, 0.0);
    const auto cellOf = [&](const openvdb::Coord& v) {
        return index((v.x() - mFirstVoxel.x()) / c, (v.y() - mFirstVoxel.y()) / c,
                     (v.z() - mFirstVoxel.z()) / c);
    };
    const double perVoxel = medium.extinction / (double(c) * c * c);
    const auto add = [&](const openvdb::Coord& v, float value) {
        const std::size_t cell = cellOf(v);
        sigmaT[cell] += perVoxel * value;
        const RenderVec3 world = mXform.indexToWorld(v.asVec3d());
        scatterOnce[cell] +=
            perVoxel * value * medium.albedo * std::exp(-sunMap.opticalDepth(world));
    };
    for (auto it = grid.tree().cbeginValueOn(); it; ++it) {
        const float value = *it;
        if (!(value > 0.0f)) continue;
        if (it.isVoxelValue()) {
            add(it.getCoord(), value);
            continue;
        }
        openvdb::CoordBBox box;
        it.getBoundingBox(box);
        for (auto v = box.begin(); v; ++v) add(*v, value);
    }

    // The cloud's cells and their couplings.
    const double gMean = (1.0 - medium.lobeBlend) * medium.g + medium.lobeBlend * medium.g2;
    std::vector<std::int32_t> id(dense, -1);
    std::vector<std::size_t> cells;
    for (std::size_t i = 0; i < dense; ++i)
        if (sigmaT[i] > 0.0) {
            id[i] = static_cast<std::int32_t>(cells.size());
            cells.push_back(i);
        }
    if (cells.empty()) return;
    const auto diffusion = [&](std::size_t cell) {
        const double s = sigmaT[cell];
        const double transport = s * (1.0 - medium.albedo) + s * medium.albedo * (1.0 - gMean);
        // Where a cell is thinner than a transport mean free path, light streams through it:
        // D is capped at the cell's size (a crude flux limiter).
        return std::min(1.0 / (3.0 * transport), mH);
    };
    System A;
    const std::size_t n = cells.size();
    A.diag.assign(n, 0.0);
    A.neighbour.assign(6 * n, -1);
    A.coupling.assign(6 * n, 0.0f);
    std::vector<double> leak(n, 0.0), source(n, 0.0);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t row) {
        const std::size_t cell = cells[row];
        const int ci = static_cast<int>(cell / (static_cast<std::size_t>(mN[1]) * mN[2]));
        const int cj = static_cast<int>((cell / mN[2]) % mN[1]);
        const int ck = static_cast<int>(cell % mN[2]);
        const double Di = diffusion(cell);
        const double s = sigmaT[cell];
        double diag = s * (1.0 - medium.albedo);
        for (int f = 0; f < 6; ++f) {
            const int axis = f / 2, step = f % 2 ? 1 : -1;
            int nb[3] = {ci, cj, ck};
            nb[axis] += step;
            const std::size_t other = index(nb[0], nb[1], nb[2]);  // the halo keeps it inside
            const double ha = h[axis];
            if (id[other] >= 0) {
                const double Dj = diffusion(other);
                const double k = 2.0 * Di * Dj / ((Di + Dj) * ha * ha);
                A.neighbour[6 * row + f] = id[other];
                A.coupling[6 * row + f] = static_cast<float>(k);
                diag += k;
            } else {
                const double k = 2.0 * Di / (ha * (ha + 4.0 * Di));  // Marshak
                leak[row] += k;
                diag += k;
            }
        }
        A.diag[row] = diag;
        source[row] = scatterOnce[cell];
    });
    std::vector<double> sun(n, 0.0), env(n, 1.0);
    mIterations = solve(A, source, sun, cancelled);
    mIterations = std::max(mIterations, solve(A, leak, env, cancelled));

    // Dense fields; an empty cell next to the cloud takes the mean of its cloud neighbours,
    // so lookups at the cloud's soft edge are not pulled toward the outside's values.
    mSun.assign(dense, 0.0f);
    mEnv.assign(dense, 1.0f);
    mD.assign(dense, 0.0f);
    for (std::size_t row = 0; row < n; ++row) {
        mSun[cells[row]] = static_cast<float>(sun[row]);
        mEnv[cells[row]] = static_cast<float>(env[row]);
        mD[cells[row]] = static_cast<float>(diffusion(cells[row]));
    }
    tbb::parallel_for(0, mN[0], [&](int i) {
        for (int j = 0; j < mN[1]; ++j)
            for (int k = 0; k < mN[2]; ++k) {
                const std::size_t cell = index(i, j, k);
                if (id[cell] >= 0) continue;
                double s = 0.0, e = 0.0, d = 0.0;
                int count = 0;
                for (int f = 0; f < 6; ++f) {
                    int nb[3] = {i, j, k};
                    nb[f / 2] += f % 2 ? 1 : -1;
                    if (nb[0] < 0 || nb[1] < 0 || nb[2] < 0 || nb[0] >= mN[0] ||
                        nb[1] >= mN[1] || nb[2] >= mN[2])
                        continue;
                    const std::int32_t row = id[index(nb[0], nb[1], nb[2])];
                    if (row < 0) continue;
                    s += sun[static_cast<std::size_t>(row)];
                    e += env[static_cast<std::size_t>(row)];
                    d += mD[cells[static_cast<std::size_t>(row)]];
                    ++count;
                }
                if (count > 0) {
                    mSun[cell] = static_cast<float>(s / count);
                    mEnv[cell] = static_cast<float>(e / count);
                    mD[cell] = static_cast<float>(d / count);
                }
            }
    });
}

RenderDiffusion::Fluence RenderDiffusion::at(const RenderVec3& p) const
{
    Fluence out;
    if (mSun.empty()) return out;
    const RenderVec3 q = mXform.worldToIndex(p);
    const double half = 0.5 * (mVoxels - 1);
    double f[3] = {(q.x() - mFirstVoxel.x() - half) / mVoxels,
                   (q.y() - mFirstVoxel.y() - half) / mVoxels,
                   (q.z() - mFirstVoxel.z() - half) / mVoxels};
    int i0[3];
    for (int a = 0; a < 3; ++a) {
        if (!(f[a] >= 0.0) || f[a] >= mN[a] - 1) return out;
        i0[a] = static_cast<int>(f[a]);
        f[a] -= i0[a];
    }
    double sun = 0.0, env = 0.0, D = 0.0;
    openvdb::Vec3d gradSun(0.0), gradEnv(0.0);  // in cell coordinates
    for (int corner = 0; corner < 8; ++corner) {
        const int d[3] = {corner & 1, (corner >> 1) & 1, (corner >> 2) & 1};
        double w = 1.0, dw[3] = {1.0, 1.0, 1.0};
        for (int a = 0; a < 3; ++a) {
            const double wa = d[a] ? f[a] : 1.0 - f[a];
            w *= wa;
            for (int b = 0; b < 3; ++b) dw[b] *= (a == b) ? (d[a] ? 1.0 : -1.0) : wa;
        }
        const std::size_t cell = index(i0[0] + d[0], i0[1] + d[1], i0[2] + d[2]);
        sun += w * mSun[cell];
        env += w * mEnv[cell];
        D += w * mD[cell];
        for (int a = 0; a < 3; ++a) {
            gradSun[a] += dw[a] * mSun[cell];
            gradEnv[a] += dw[a] * mEnv[cell];
        }
    }
    out.sun = sun;
    out.env = env;
    // World gradients: cell coordinates are index coordinates / mVoxels; the transform's
    // inverse Jacobian transpose takes an index-space gradient to world space.
    const auto toWorld = [&](const openvdb::Vec3d& g) {
        return mXform.baseMap()->applyIJT(g / double(mVoxels));
    };
    out.sunFlux = toWorld(gradSun) * -D;
    out.envFlux = toWorld(gradEnv) * -D;
    return out;
}

}  // namespace cg::algo
