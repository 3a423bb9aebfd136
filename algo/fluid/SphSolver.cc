#include "algo/fluid/SphSolver.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

namespace cg::algo {

namespace {

constexpr std::size_t kMaxNeighbours = 96;  // more means the flow blew up
constexpr std::size_t kStrideMargin = 8;    // spare slots per row over the last fullest row
constexpr std::size_t kGrain = 1024;        // fixed split for the deterministic reductions

template <typename F>
void forParticles(std::size_t n, F&& f)
{
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i != r.end(); ++i) f(i);
                      });
}

/// Two doubles side by side, one lane per particle: each lane does the scalar arithmetic of
/// its own particle in the same order, so a pair gives the same bits as two single visits,
/// with half the arithmetic instructions (the neighbour passes are bound by them).
using Pair = double __attribute__((vector_size(16)));

Pair pairOf(double a, double b) { return Pair{a, b}; }

/// f(a, b) for the particles of [0, n) two at a time, b = a + 1 (or b = a, a lone last
/// particle of a range, when `pair` is false).
template <typename F>
void forParticlePairs(std::size_t n, F&& f)
{
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i < r.end(); i += 2) {
                              const bool pair = i + 1 < r.end();
                              f(i, pair ? i + 1 : i, pair);
                          }
                      });
}

/// Sum of f(i) over [0, n), the same bits for any thread count.
template <typename F>
double deterministicSum(std::size_t n, F&& f)
{
    return tbb::parallel_deterministic_reduce(
        tbb::blocked_range<std::size_t>(0, n, kGrain), 0.0,
        [&](const tbb::blocked_range<std::size_t>& r, double acc) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) acc += f(i);
            return acc;
        },
        [](double a, double b) { return a + b; });
}

template <typename F>
double parallelMax(std::size_t n, F&& f)
{
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, n, kGrain), 0.0,
        [&](const tbb::blocked_range<std::size_t>& r, double acc) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) acc = std::max(acc, f(i));
            return acc;
        },
        [](double a, double b) { return std::max(a, b); });
}

int cellsAlong(double lo, double hi, double dx)
{
    const double n = std::round((hi - lo) / dx);
    if (!(n >= 1.0) || n > 4096.0) throw std::invalid_argument("SphSolver: bad box size");
    return static_cast<int>(n);
}

/// The cell grid over the box and its two wall layers, cells of the kernel support.
SphGrid makeGrid(const SphSettings& s, const double lo[3], const double hi[3])
{
    double glo[3], ghi[3];
    for (int a = 0; a < 3; ++a) {
        glo[a] = lo[a] - 2.0 * s.spacing;
        ghi[a] = lo[a] + (cellsAlong(lo[a], hi[a], s.spacing) + 2.0) * s.spacing;
    }
    return SphGrid(glo, ghi, s.supportFactor * s.spacing);
}

}  // namespace

SphSolver::SphSolver(const SphSettings& s, const double lo[3], const double hi[3])
    : mSettings(s), mKernel(s.supportFactor * s.spacing), mGrid(makeGrid(s, lo, hi))
{
    if (!(s.spacing > 0.0) || !(s.supportFactor >= 1.0) || s.supportFactor > 3.0)
        throw std::invalid_argument("SphSolver: bad spacing or support");
    const double dx = s.spacing;
    int n[3];
    for (int a = 0; a < 3; ++a) {
        n[a] = cellsAlong(lo[a], hi[a], dx);
        mLo[a] = lo[a];
        mHi[a] = lo[a] + n[a] * dx;
    }
    // The fluid lattice, then two layers of wall lattice around it.
    auto pushLattice = [&](bool walls) {
        for (int k = -2; k < n[2] + 2; ++k)
            for (int j = -2; j < n[1] + 2; ++j)
                for (int i = -2; i < n[0] + 2; ++i) {
                    const bool inside =
                        i >= 0 && j >= 0 && k >= 0 && i < n[0] && j < n[1] && k < n[2];
                    if (inside == walls) continue;
                    mX.push_back(mLo[0] + (i + 0.5) * dx);
                    mX.push_back(mLo[1] + (j + 0.5) * dx);
                    mX.push_back(mLo[2] + (k + 0.5) * dx);
                }
    };
    pushLattice(false);
    mFluid = mX.size() / 3;
    pushLattice(true);

    mMass = s.airDensity * dx * dx * dx;
    // rho0 from a particle with a full lattice neighbourhood, so a resting lattice has zero
    // density error.
    const double h = mKernel.support();
    const int reach = static_cast<int>(std::ceil(h / dx));
    double w = 0.0;
    for (int k = -reach; k <= reach; ++k)
        for (int j = -reach; j <= reach; ++j)
            for (int i = -reach; i <= reach; ++i)
                w += mKernel.value(dx * std::sqrt(static_cast<double>(i * i + j * j + k * k)));
    mRho0 = mMass * w;

    const std::size_t all = mX.size() / 3;
    mV.assign(3 * all, 0.0);
    mT.resize(mFluid);
    mQv.resize(mFluid);
    mQc.assign(mFluid, 0.0);
    for (std::size_t i = 0; i < mFluid; ++i) {
        mT[i] = ambientTemperature(s.thermo, mX[3 * i + 2]);
        mQv[i] = ambientVapour(s.thermo, mX[3 * i + 2]);
    }
    mRho.assign(mFluid, mRho0);
    mP.assign(all, 0.0);
    mAcc.assign(3 * mFluid, 0.0);
    mAccP.assign(3 * mFluid, 0.0);
    mDT.assign(mFluid, 0.0);
    mDQ.assign(mFluid, 0.0);
    mTheta.assign(mFluid, 0.0);
    mGradSq.assign(mFluid, 0.0);
    mVapour.assign(mFluid, 0.0);
    mNbrCount.resize(mFluid);
}

double SphSolver::totalTemperature() const
{
    return deterministicSum(mFluid, [&](std::size_t i) { return mT[i]; });
}

double SphSolver::stableTimeStep() const
{
    const double h = mKernel.support();
    const double dx = mSettings.spacing;
    const double vmax = parallelMax(mFluid, [&](std::size_t i) {
        const double* v = &mV[3 * i];
        return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    });
    // The forces of the last sub-step, and the buoyancy now: before the first sub-step the
    // forces are not known yet, and a warm blob must not start with a huge step.
    const ThermoSettings& th = mSettings.thermo;
    const bool lift = mSettings.buoyancy;
    const double amax = parallelMax(mFluid, [&](std::size_t i) {
        const double* a = &mAcc[3 * i];
        const double b = lift ? buoyancy(th, mX[3 * i + 2], mT[i], mQv[i], mQc[i]) : 0.0;
        return std::max(std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]), std::fabs(b));
    });
    double dt = 1e30;
    if (vmax > 0.0) dt = std::min(dt, mSettings.cfl * dx / vmax);
    if (amax > 0.0) dt = std::min(dt, 0.25 * std::sqrt(h / amax));
    const double diff = std::max(mSettings.viscosity, mSettings.conduction);
    if (diff > 0.0) dt = std::min(dt, 0.1 * dx * dx / diff);
    return dt;
}

void SphSolver::buildNeighbours()
{
    mGrid.build(mX.data(), mX.size() / 3);
    // Rows of mStride slots, as narrow as the fullest row of the last build allows: the passes
    // stream these lists many times per sub-step, so wide, mostly empty rows cost bandwidth.
    // A build whose fullest row does not fit is redone with wider rows.
    mStride = mStrideHint;
    for (;;) {
        mNbr.resize(mStride * mFluid);
        mGradF.resize(mStride * mFluid);
        fillNeighbourRows();
        const auto fullest = static_cast<std::size_t>(
            parallelMax(mFluid, [&](std::size_t i) { return double(mNbrCount[i]); }));
        if (fullest > kMaxNeighbours)
            throw std::runtime_error("SPH: more than " + std::to_string(kMaxNeighbours) +
                                     " neighbours; the simulation became unstable "
                                     "(use a smaller time step or CFL number)");
        mStrideHint = fullest + kStrideMargin;
        if (fullest <= mStride) return;
        mStride = mStrideHint;
    }
}

void SphSolver::fillNeighbourRows()
{
    const double h = mKernel.support();
    forParticles(mFluid, [&](std::size_t i) {
        const double* xi = &mX[3 * i];
        std::size_t c = 0;
        std::uint32_t* out = &mNbr[mStride * i];
        float* f = &mGradF[mStride * i];
        double sum[3] = {0, 0, 0}, sq = 0.0;
        mGrid.forEachNeighbour(xi, h, [&](std::uint32_t j) {
            if (j == i) return;
            if (c++ >= mStride) return;  // only counted: the row is too narrow
            const std::size_t k = c - 1;
            const double* xj = &mX[3 * static_cast<std::size_t>(j)];
            const double d[3] = {xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]};
            const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            // grad W_ij = F_ij (x_i - x_j); only F is stored, halving what the passes read.
            f[k] = static_cast<float>(r > 1e-12 * h ? mKernel.derivative(r) / r : 0.0);
            const double gw[3] = {f[k] * d[0], f[k] * d[1], f[k] * d[2]};
            out[k] = j;
            // The geometric part of IISPH's diagonal a_ii, for the pressure preconditioner.
            for (int a = 0; a < 3; ++a) sum[a] += gw[a];
            if (j < mFluid) sq += gw[0] * gw[0] + gw[1] * gw[1] + gw[2] * gw[2];
        });
        mNbrCount[i] = static_cast<std::uint16_t>(std::min<std::size_t>(c, kMaxNeighbours + 1));
        mGradSq[i] = sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2] + sq;
    });
}

void SphSolver::computeDensity()
{
    const double w0 = mKernel.value(0.0);
    forParticles(mFluid, [&](std::size_t i) {
        const double* xi = &mX[3 * i];
        double w = w0;
        const std::uint32_t* nb = &mNbr[mStride * i];
        for (std::size_t c = 0; c < mNbrCount[i]; ++c) {
            const double* xj = &mX[3 * static_cast<std::size_t>(nb[c])];
            const double d[3] = {xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]};
            w += mKernel.value(std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
        }
        mRho[i] = mMass * w;
    });
}

void SphSolver::computeForcesAndHeat()
{
    const double h = mKernel.support();
    const double eta2 = 0.01 * h * h;
    const double visc = 10.0 * mSettings.viscosity * mMass / mRho0;  // 2 (d + 2) nu m / rho0
    const double cond = 2.0 * mSettings.conduction * mMass / mRho0;  // Brookshaw Laplacian
    const ThermoSettings& th = mSettings.thermo;
    // Departures from the ambient profile, once per particle (the profile costs two exp).
    forParticles(mFluid, [&](std::size_t i) {
        mTheta[i] = mT[i] - ambientTemperature(th, mX[3 * i + 2]);
        mVapour[i] = mQv[i] - ambientVapour(th, mX[3 * i + 2]);
    });
    forParticles(mFluid, [&](std::size_t i) {
        const double* xi = &mX[3 * i];
        const double* vi = &mV[3 * i];
        const double thetaI = mTheta[i];
        const double vapI = mVapour[i];
        double a[3] = {0, 0, 0}, dT = 0.0, dQ = 0.0;
        const std::uint32_t* nb = &mNbr[mStride * i];
        const float* f = &mGradF[mStride * i];
        for (std::size_t c = 0; c < mNbrCount[i]; ++c) {
            const std::size_t j = nb[c];
            const double* xj = &mX[3 * j];
            if (j >= mFluid) continue;  // free-slip, adiabatic, dry walls
            const double* vj = &mV[3 * j];
            const double d[3] = {xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]};
            const double gw[3] = {f[c] * d[0], f[c] * d[1], f[c] * d[2]};
            const double xg = (d[0] * gw[0] + d[1] * gw[1] + d[2] * gw[2]) /
                              (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + eta2);
            const double vx =
                (vi[0] - vj[0]) * d[0] + (vi[1] - vj[1]) * d[1] + (vi[2] - vj[2]) * d[2];
            const double sv = visc * vx / (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + eta2);
            a[0] += sv * gw[0];
            a[1] += sv * gw[1];
            a[2] += sv * gw[2];
            // Conduction of the departures from the ambient profile (lap T_e = 0, so this is
            // alpha lap T of Eq. 2), pairwise antisymmetric: heat is only moved, never made.
            dT += cond * (thetaI - mTheta[j]) * xg;
            dQ += cond * (vapI - mVapour[j]) * xg;
        }
        if (mSettings.buoyancy) a[2] += buoyancy(th, xi[2], mT[i], mQv[i], mQc[i]);
        mAcc[3 * i] = a[0];
        mAcc[3 * i + 1] = a[1];
        mAcc[3 * i + 2] = a[2];
        mDT[i] = dT;
        mDQ[i] = dQ;
    });
}

template <typename F>
void SphSolver::forNeighbourPairs(std::size_t a, std::size_t b, bool pair, F&& f) const
{
    const std::size_t na = mNbrCount[a], nb = pair ? mNbrCount[b] : 0;
    const std::uint32_t* rowA = &mNbr[mStride * a];
    const std::uint32_t* rowB = &mNbr[mStride * b];
    const float* fA = &mGradF[mStride * a];
    const float* fB = &mGradF[mStride * b];
    const std::size_t common = std::min(na, nb);
    std::size_t c = 0;
    for (; c < common; ++c) f(rowA[c], rowB[c], pairOf(fA[c], fB[c]));
    for (; c < na; ++c) f(rowA[c], b, pairOf(fA[c], 0.0));
    for (; c < nb; ++c) f(a, rowB[c], pairOf(0.0, fB[c]));
}

void SphSolver::pressureAcceleration(const std::vector<double>& p, std::vector<double>& acc) const
{
    // a_i = -m/rho0^2 [ sum_fluid (p_i + p_j) grad W_ij + sum_wall p_i grad W_iw ]: the
    // wall term (p_wall = 0) makes this the exact adjoint of densityChange, so the pressure
    // system is symmetric and conjugate gradients apply. p holds the walls' zeros after the
    // fluid, so p_i + p_wall is p_i (or +0 for p_i = -0, a term of +-0 that changes no sum).
    const double s0 = -mMass / (mRho0 * mRho0);
    forParticlePairs(mFluid, [&](std::size_t ia, std::size_t ib, bool pair) {
        const double* xa = &mX[3 * ia];
        const double* xb = &mX[3 * ib];
        const Pair xi[3] = {pairOf(xa[0], xb[0]), pairOf(xa[1], xb[1]), pairOf(xa[2], xb[2])};
        const Pair pi = pairOf(p[ia], p[ib]);
        Pair a[3] = {};
        forNeighbourPairs(ia, ib, pair, [&](std::size_t ja, std::size_t jb, Pair f) {
            const double* xja = &mX[3 * ja];
            const double* xjb = &mX[3 * jb];
            const Pair s = s0 * f * (pi + pairOf(p[ja], p[jb]));
            a[0] += s * (xi[0] - pairOf(xja[0], xjb[0]));
            a[1] += s * (xi[1] - pairOf(xja[1], xjb[1]));
            a[2] += s * (xi[2] - pairOf(xja[2], xjb[2]));
        });
        for (int k = 0; k < 3; ++k) {
            acc[3 * ia + k] = a[k][0];
            if (pair) acc[3 * ib + k] = a[k][1];
        }
    });
}

void SphSolver::densityChange(const std::vector<double>& v, double scale,
                              std::vector<double>& out) const
{
    // out_i = scale sum_j m (v_i - v_j) . grad W_ij, walls at rest: v holds the walls' zero
    // velocities after the fluid's, and v_i - 0 is v_i exactly.
    forParticlePairs(mFluid, [&](std::size_t ia, std::size_t ib, bool pair) {
        const double* xa = &mX[3 * ia];
        const double* xb = &mX[3 * ib];
        const double* va = &v[3 * ia];
        const double* vb = &v[3 * ib];
        const Pair xi[3] = {pairOf(xa[0], xb[0]), pairOf(xa[1], xb[1]), pairOf(xa[2], xb[2])};
        const Pair vi[3] = {pairOf(va[0], vb[0]), pairOf(va[1], vb[1]), pairOf(va[2], vb[2])};
        Pair div = {};
        forNeighbourPairs(ia, ib, pair, [&](std::size_t ja, std::size_t jb, Pair f) {
            const double* xja = &mX[3 * ja];
            const double* xjb = &mX[3 * jb];
            const double* vja = &v[3 * ja];
            const double* vjb = &v[3 * jb];
            div += f * ((vi[0] - pairOf(vja[0], vjb[0])) * (xi[0] - pairOf(xja[0], xjb[0])) +
                        (vi[1] - pairOf(vja[1], vjb[1])) * (xi[1] - pairOf(xja[1], xjb[1])) +
                        (vi[2] - pairOf(vja[2], vjb[2])) * (xi[2] - pairOf(xja[2], xjb[2])));
        });
        out[ia] = scale * mMass * div[0];
        if (pair) out[ib] = scale * mMass * div[1];
    });
}

void SphSolver::solvePressure(double dt)
{
    // Implicit incompressible SPH: find p so that the density predicted after the step,
    // rho*_i = rho_i + dt sum_j m (v*_i - v*_j) . grad W_ij with v* = v + dt (a + a_p(p)),
    // equals rho0. The map p -> rho* is linear, symmetric and positive definite
    // (M = -dt^2 D a_p, D the divergence above), so it is solved by conjugate gradients
    // with IISPH's per-particle diagonal a_ii as preconditioner, warm-started from the last
    // pressure. Pressures may be negative: the box is closed, there is no free surface.
    const std::size_t n = mFluid;
    std::vector<double>& vstar = mWork[0];
    std::vector<double>& accD = mWork[1];
    std::vector<double>& r = mWork[2];
    std::vector<double>& z = mWork[3];
    std::vector<double>& d = mWork[4];
    std::vector<double>& q = mWork[5];
    std::vector<double>& diag = mWork[6];
    // The passes read the walls' velocities and pressures after the fluid's: zeros.
    const std::size_t all = mX.size() / 3;
    for (std::vector<double>* w : {&vstar, &accD}) w->assign(3 * all, 0.0);
    d.assign(all, 0.0);
    for (std::vector<double>* w : {&r, &z, &q, &diag}) w->resize(n);

    const double scale = dt * dt * mMass * mMass / (mRho0 * mRho0);
    forParticles(
        n, [&](std::size_t i) { diag[i] = mGradSq[i] > 0.0 ? 1.0 / (scale * mGradSq[i]) : 0.0; });

    // Residual r = (rho* - rho0) / rho0 at the warm-start pressure; the unknown is p / rho0.
    pressureAcceleration(mP, mAccP);
    forParticles(n, [&](std::size_t i) {
        for (int k = 0; k < 3; ++k)
            vstar[3 * i + k] = mV[3 * i + k] + dt * (mAcc[3 * i + k] + mAccP[3 * i + k]);
    });
    densityChange(vstar, dt, r);
    forParticles(n, [&](std::size_t i) { r[i] = (mRho[i] + r[i] - mRho0) / mRho0; });
    auto maxAbs = [&](const std::vector<double>& e) {
        return parallelMax(n, [&](std::size_t i) { return std::fabs(e[i]); });
    };
    auto dot = [&](const std::vector<double>& a, const std::vector<double>& b) {
        return deterministicSum(n, [&](std::size_t i) { return a[i] * b[i]; });
    };
    int it = 0;
    double worst = maxAbs(r);
    forParticles(n, [&](std::size_t i) { d[i] = z[i] = diag[i] * r[i]; });
    double rz = dot(r, z);
    while (worst > mSettings.maxDensityError && it < mSettings.maxIterations && rz > 0.0) {
        // q = M d = -dt^2 D a_p(d); d is in units of p / rho0.
        pressureAcceleration(d, accD);
        densityChange(accD, -dt * dt, q);
        const double dq = dot(d, q);
        if (!(dq > 0.0)) break;
        const double alpha = rz / dq;
        forParticles(n, [&](std::size_t i) {
            mP[i] += alpha * d[i] * mRho0;
            for (int k = 0; k < 3; ++k) mAccP[3 * i + k] += alpha * mRho0 * accD[3 * i + k];
            r[i] -= alpha * q[i];
            z[i] = diag[i] * r[i];
        });
        ++it;
        worst = maxAbs(r);
        const double rzNew = dot(r, z);
        const double beta = rzNew / rz;
        rz = rzNew;
        forParticles(n, [&](std::size_t i) { d[i] = z[i] + beta * d[i]; });
    }
    mStats.iterations = it;
    mTotalIterations += it;
    mStats.meanDensityError = deterministicSum(n, [&](std::size_t i) { return std::fabs(r[i]); }) /
                              static_cast<double>(n);
    mStats.solverDensityError = worst;
}

void SphSolver::integrate(double dt)
{
    const ThermoSettings& th = mSettings.thermo;
    const SphSource& src = mSettings.source;
    const bool sourceOn = src.enabled && mTime < src.duration;
    const double relax = std::min(1.0, dt / std::max(src.relaxTime, 1e-9));
    const double margin = 0.25 * mSettings.spacing;
    forParticles(mFluid, [&](std::size_t i) {
        double* x = &mX[3 * i];
        double* v = &mV[3 * i];
        for (int a = 0; a < 3; ++a) {
            v[a] += dt * (mAcc[3 * i + a] + mAccP[3 * i + a]);
            x[a] += dt * v[a];
            // The wall layers keep particles in; this only guards against a rare overshoot.
            if (x[a] < mLo[a] + margin) {
                x[a] = mLo[a] + margin;
                v[a] = std::max(v[a], 0.0);
            } else if (x[a] > mHi[a] - margin) {
                x[a] = mHi[a] - margin;
                v[a] = std::min(v[a], 0.0);
            }
        }
        // Eq. 2 along the particle path: conduction (entrainment), -Gamma u_z, then Q C_c.
        mT[i] += dt * mDT[i];
        mQv[i] = std::max(0.0, mQv[i] + dt * mDQ[i]);
        if (mSettings.thermodynamics) mT[i] -= dt * th.dryLapse * v[2];
        if (sourceOn) {
            const double d[3] = {x[0] - src.centre[0], x[1] - src.centre[1], x[2] - src.centre[2]};
            if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < src.radius * src.radius) {
                const double ts = ambientTemperature(th, x[2]) + src.excessTemperature;
                const double qs = src.humidity * saturationHumidity(ts, pressureAt(th, x[2]));
                mT[i] += relax * (ts - mT[i]);
                mQv[i] += relax * (qs - mQv[i]);
            }
        }
        if (mSettings.thermodynamics) condense(th, x[2], mT[i], mQv[i], mQc[i]);
    });
}

void SphSolver::step(double dt)
{
    if (!(dt > 0.0)) throw std::invalid_argument("SphSolver::step: dt must be positive");
    buildNeighbours();
    computeDensity();
    computeForcesAndHeat();
    solvePressure(dt);
    integrate(dt);
    mTime += dt;
    mStats.maxDensityError =
        parallelMax(mFluid, [&](std::size_t i) { return std::fabs(mRho[i] - mRho0) / mRho0; });
    mStats.maxSpeed = parallelMax(mFluid, [&](std::size_t i) {
        const double* v = &mV[3 * i];
        return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    });
}

int SphSolver::advance(double duration, const std::function<void()>& poll)
{
    if (!(duration > 0.0))
        throw std::invalid_argument("SphSolver::advance: duration must be positive");
    double left = duration;
    int steps = 0;
    while (left > 1e-9 * duration) {
        if (poll) poll();
        // Re-evaluate the limit each sub-step; split what is left evenly.
        const double limit = stableTimeStep();
        const int n = static_cast<int>(std::ceil(left / limit - 1e-9));
        const double dt = left / std::max(n, 1);
        step(dt);
        left -= dt;
        ++steps;
    }
    return steps;
}

}  // namespace cg::algo
