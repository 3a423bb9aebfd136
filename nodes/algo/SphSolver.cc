#include "nodes/algo/SphSolver.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

namespace cg::algo {

namespace {

constexpr std::size_t kMaxNeighbours = 96;
constexpr std::size_t kGrain = 1024;  // fixed split for the deterministic reductions

template <typename F>
void forParticles(std::size_t n, F&& f)
{
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i != r.end(); ++i) f(i);
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
    // rho0 and PCISPH's delta from a particle with a full lattice neighbourhood, so a resting
    // lattice has zero density error.
    const double h = mKernel.support();
    const int reach = static_cast<int>(std::ceil(h / dx));
    double w = 0.0, sumG[3] = {0, 0, 0}, sumGG = 0.0;
    for (int k = -reach; k <= reach; ++k)
        for (int j = -reach; j <= reach; ++j)
            for (int i = -reach; i <= reach; ++i) {
                const double x[3] = {-i * dx, -j * dx, -k * dx};
                const double r = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
                w += mKernel.value(r);
                double g[3];
                mKernel.gradient(x, r, g);
                for (int a = 0; a < 3; ++a) sumG[a] += g[a];
                sumGG += g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
            }
    mRho0 = mMass * w;
    const double beta = 2.0 * (mMass / mRho0) * (mMass / mRho0);  // times dt^2
    mDelta = 1.0 / (beta * (sumG[0] * sumG[0] + sumG[1] * sumG[1] + sumG[2] * sumG[2] + sumGG));

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
    mNbr.resize(kMaxNeighbours * mFluid);
    mNbrCount.resize(mFluid);
    mGradW.resize(3 * kMaxNeighbours * mFluid);
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
    const double amax = parallelMax(mFluid, [&](std::size_t i) {
        const double* a = &mAcc[3 * i];
        return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
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
    const std::size_t all = mX.size() / 3;
    mGrid.build(mX.data(), all);
    const double h = mKernel.support();
    forParticles(mFluid, [&](std::size_t i) {
        const double* xi = &mX[3 * i];
        std::size_t c = 0;
        std::uint32_t* out = &mNbr[kMaxNeighbours * i];
        float* g = &mGradW[3 * kMaxNeighbours * i];
        bool overflow = false;
        mGrid.forEachNeighbour(mX.data(), xi, h, [&](std::uint32_t j) {
            if (j == i) return;
            if (c == kMaxNeighbours) {
                overflow = true;
                return;
            }
            const double* xj = &mX[3 * static_cast<std::size_t>(j)];
            const double d[3] = {xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]};
            const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            double gw[3];
            mKernel.gradient(d, r, gw);
            out[c] = j;
            g[3 * c] = static_cast<float>(gw[0]);
            g[3 * c + 1] = static_cast<float>(gw[1]);
            g[3 * c + 2] = static_cast<float>(gw[2]);
            ++c;
        });
        if (overflow)
            throw std::runtime_error("SPH: more than " + std::to_string(kMaxNeighbours) +
                                     " neighbours; the simulation became unstable "
                                     "(use a smaller time step or CFL number)");
        mNbrCount[i] = static_cast<std::uint16_t>(c);
    });
}

void SphSolver::computeDensity()
{
    const double w0 = mKernel.value(0.0);
    forParticles(mFluid, [&](std::size_t i) {
        const double* xi = &mX[3 * i];
        double w = w0;
        const std::uint32_t* nb = &mNbr[kMaxNeighbours * i];
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
    forParticles(mFluid, [&](std::size_t i) {
        const double* xi = &mX[3 * i];
        const double* vi = &mV[3 * i];
        const double thetaI = mT[i] - ambientTemperature(th, xi[2]);
        const double vapI = mQv[i] - ambientVapour(th, xi[2]);
        double a[3] = {0, 0, 0}, dT = 0.0, dQ = 0.0;
        const std::uint32_t* nb = &mNbr[kMaxNeighbours * i];
        const float* g = &mGradW[3 * kMaxNeighbours * i];
        for (std::size_t c = 0; c < mNbrCount[i]; ++c) {
            const std::size_t j = nb[c];
            if (j >= mFluid) continue;  // free-slip, adiabatic, dry walls
            const double* xj = &mX[3 * j];
            const double* vj = &mV[3 * j];
            const double d[3] = {xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]};
            const double gw[3] = {g[3 * c], g[3 * c + 1], g[3 * c + 2]};
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
            const double thetaJ = mT[j] - ambientTemperature(th, xj[2]);
            const double vapJ = mQv[j] - ambientVapour(th, xj[2]);
            dT += cond * (thetaI - thetaJ) * xg;
            dQ += cond * (vapI - vapJ) * xg;
        }
        if (mSettings.buoyancy) a[2] += buoyancy(th, xi[2], mT[i], mQv[i], mQc[i]);
        mAcc[3 * i] = a[0];
        mAcc[3 * i + 1] = a[1];
        mAcc[3 * i + 2] = a[2];
        mDT[i] = dT;
        mDQ[i] = dQ;
    });
}

void SphSolver::solvePressure(double dt)
{
    // Predict rho*_i = rho_i + dt sum_j m (v*_i - v*_j) . grad W_ij with v* = v + dt (a + a_p),
    // correct p_i += delta (rho*_i - rho0), repeat (PCISPH). Walls: v = 0, p_wall = p_i.
    // Relaxed by one half: the full prototype delta over-corrects when neighbours move too
    // (the Jacobi iteration then diverges), as IISPH's omega = 0.5.
    const double delta = 0.5 * mDelta / (dt * dt);
    const double invRho2 = 1.0 / (mRho0 * mRho0);
    // Warm start from half the last pressure (as IISPH), so a steady pressure field (a
    // resting column, a wall under load) is not rebuilt from zero every sub-step.
    for (std::size_t i = 0; i < mFluid; ++i) mP[i] *= 0.5;
    std::vector<double> vstar(3 * mFluid);
    std::vector<double> err(mFluid);
    int it = 0;
    double mean = 0.0;
    for (;;) {
        forParticles(mFluid, [&](std::size_t i) {
            const std::uint32_t* nb = &mNbr[kMaxNeighbours * i];
            const float* g = &mGradW[3 * kMaxNeighbours * i];
            double a[3] = {0, 0, 0};
            for (std::size_t c = 0; c < mNbrCount[i]; ++c) {
                const std::size_t j = nb[c];
                const double pj = j < mFluid ? mP[j] : mP[i];
                const double s = -mMass * (mP[i] + pj) * invRho2;
                a[0] += s * g[3 * c];
                a[1] += s * g[3 * c + 1];
                a[2] += s * g[3 * c + 2];
            }
            for (int k = 0; k < 3; ++k) {
                mAccP[3 * i + k] = a[k];
                vstar[3 * i + k] = mV[3 * i + k] + dt * (mAcc[3 * i + k] + a[k]);
            }
        });
        forParticles(mFluid, [&](std::size_t i) {
            const double* vi = &vstar[3 * i];
            const std::uint32_t* nb = &mNbr[kMaxNeighbours * i];
            const float* g = &mGradW[3 * kMaxNeighbours * i];
            double div = 0.0;
            for (std::size_t c = 0; c < mNbrCount[i]; ++c) {
                const std::size_t j = nb[c];
                const double* vj = j < mFluid ? &vstar[3 * j] : nullptr;
                const double dv[3] = {vi[0] - (vj ? vj[0] : 0.0), vi[1] - (vj ? vj[1] : 0.0),
                                      vi[2] - (vj ? vj[2] : 0.0)};
                div += dv[0] * g[3 * c] + dv[1] * g[3 * c + 1] + dv[2] * g[3 * c + 2];
            }
            err[i] = mRho[i] + dt * mMass * div - mRho0;
        });
        mean = deterministicSum(mFluid, [&](std::size_t i) { return std::fabs(err[i]); }) /
               (static_cast<double>(mFluid) * mRho0);
        if ((it >= mSettings.minIterations && mean < mSettings.maxDensityError) ||
            it >= mSettings.maxIterations)
            break;
        // Pressures stay >= 0: negative pressure would pull particles into clumps (the SPH
        // tensile instability); a rarefied spot is filled by its compressed neighbours.
        forParticles(mFluid, [&](std::size_t i) { mP[i] = std::max(0.0, mP[i] + delta * err[i]); });
        ++it;
    }
    mStats.iterations = it;
    mStats.meanDensityError = mean;
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
