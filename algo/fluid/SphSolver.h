#pragma once
/// The particle fluid of Sec. 4: the incompressible Navier-Stokes equations (Eq. 1) with the
/// thermodynamics of Eq. 2, by SPH with an implicit pressure solve (IISPH's equation, Ihmsen et
/// al. 2014, solved by conjugate gradients with IISPH's diagonal as preconditioner).
///
/// Air fills a closed box, sampled by fluid particles on a cubic lattice of spacing dx; the
/// walls are two frozen layers of the same lattice outside the box (so a resting box has
/// exactly the rest density everywhere, corners included). The pressure solve makes the
/// density predicted after each sub-step equal rho0 within maxDensityError (max norm). Buoyancy is
/// the external force of Eq. 1 (Boussinesq: the hydrostatic part of pressure balances gravity and
/// is left out). Each particle carries temperature T, water vapour q_v and condensed water q_c.
///
/// Every per-particle loop reads neighbours and writes only its own particle, and sums over
/// particles use a fixed split (tbb::parallel_deterministic_reduce), so results are
/// bit-identical whatever the thread count.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "algo/fluid/SphGrid.h"
#include "algo/fluid/SphKernel.h"
#include "algo/fluid/SphThermo.h"

namespace cg::algo {

/// A warm, moist region near the floor that feeds the thermal (ours: the paper does not say
/// how its thermal starts). Particles inside relax towards T_e(z) + excessTemperature and a
/// relative humidity `humidity` at that temperature, with time constant relaxTime.
struct SphSource {
    bool enabled = false;
    double centre[3] = {0.0, 0.0, 0.0};  ///< m
    double radius = 100.0;               ///< m
    double excessTemperature = 2.0;      ///< K above the ambient T_e(z)
    double humidity = 0.9;               ///< relative humidity of the source air, 0..1
    double relaxTime = 10.0;             ///< s
    double duration = 1e30;              ///< s of simulated time the source stays on
};

struct SphSettings {
    double spacing = 20.0;       ///< dx, particle spacing at rest, m (value ours)
    double supportFactor = 2.0;  ///< kernel support H = supportFactor dx (value ours)
    double airDensity = 1.2;     ///< rho of Eq. 1, kg/m^3; particle mass m = rho dx^3
    double viscosity = 1.0;      ///< kinematic viscosity mu of Eq. 1, m^2/s (an eddy value, ours)
    double conduction = 1.0;     ///< alpha of Eq. 2, thermal diffusion (entrainment), m^2/s (ours)
    double cfl = 0.4;            ///< time step <= cfl dx / |u|_max (value ours)
    double maxDensityError = 0.002;  ///< the pressure solve stops when the predicted density
                                     ///< error max |rho* - rho0| / rho0 is below this
    int maxIterations = 60;          ///< pressure solve (CG) iterations at most per sub-step
    bool buoyancy = true;            ///< buoyancy as the external force f of Eq. 1
    bool thermodynamics = true;      ///< the -Gamma u_z and Q C_c terms of Eq. 2
    ThermoSettings thermo;
    SphSource source;
};

/// Statistics of the last sub-step.
struct SphStepStats {
    int iterations = 0;
    double meanDensityError = 0.0;    ///< mean |rho* - rho0| / rho0 after the pressure solve
    double solverDensityError = 0.0;  ///< max |rho* - rho0| / rho0 after the pressure solve
    double maxDensityError = 0.0;     ///< max |rho - rho0| / rho0 of the true SPH density at
                                      ///< the start of the sub-step (after the last move)
    double maxSpeed = 0.0;            ///< m/s
};

class SphSolver {
public:
    /// Fills the box [lo, hi] (m) with a lattice of spacing dx at rest, each particle in the
    /// ambient state of its height (T_e(z), q_v,e(z), q_c = 0). The box is rounded to whole
    /// cells of dx from `lo`.
    SphSolver(const SphSettings& settings, const double lo[3], const double hi[3]);

    std::size_t size() const { return mFluid; }
    const SphSettings& settings() const { return mSettings; }
    double restDensity() const { return mRho0; }
    double particleMass() const { return mMass; }
    double time() const { return mTime; }
    const double* boxLo() const { return mLo; }
    const double* boxHi() const { return mHi; }

    /// State, particle i at [3 i] (vectors) or [i]: position m, velocity m/s, T degrees C,
    /// q_v and q_c kg/kg. Writable, for setting up scenes and tests.
    std::vector<double>& positions() { return mX; }  ///< fluid first, then the frozen walls
    std::vector<double>& velocities() { return mV; }
    std::vector<double>& temperatures() { return mT; }
    std::vector<double>& vapour() { return mQv; }
    std::vector<double>& condensed() { return mQc; }
    const std::vector<double>& densities() const { return mRho; }

    /// The largest stable sub-step: CFL on the speed, the viscous and conduction limits and the
    /// force limit (s).
    double stableTimeStep() const;
    /// One sub-step of dt seconds.
    void step(double dt);
    /// Advances by `duration` seconds in equal CFL-limited sub-steps; returns their number.
    /// `poll` is called between sub-steps (it may throw to cancel).
    int advance(double duration, const std::function<void()>& poll = {});

    const SphStepStats& lastStats() const { return mStats; }
    /// Pressure-solve iterations over all sub-steps so far.
    long long totalPressureIterations() const { return mTotalIterations; }

    /// Sum over fluid particles of T (K sum), with a fixed summation order.
    double totalTemperature() const;

private:
    void buildNeighbours();
    /// One try at the neighbour rows of width mStride; mNbrCount gets the true counts.
    void fillNeighbourRows();
    void computeDensity();
    void computeForcesAndHeat();
    void solvePressure(double dt);
    /// f(ja, jb, F) for the neighbour slots of particles a and b side by side, F holding
    /// both slots' F_ij; past the shorter row, that lane visits its own particle with F = 0
    /// (a term of +-0, which changes no sum that starts at +0). b = a when `pair` is false.
    template <typename F>
    void forNeighbourPairs(std::size_t a, std::size_t b, bool pair, F&& f) const;
    /// acc = the pressure acceleration of the pressures p (fluid particles, then the walls'
    /// zeros).
    void pressureAcceleration(const std::vector<double>& p, std::vector<double>& acc) const;
    /// out_i = scale sum_j m (v_i - v_j) . grad W_ij; v holds the walls' zeros after the
    /// fluid.
    void densityChange(const std::vector<double>& v, double scale, std::vector<double>& out) const;
    void integrate(double dt);

    SphSettings mSettings;
    SphKernel mKernel;
    SphGrid mGrid;
    double mLo[3], mHi[3];
    double mMass = 0.0, mRho0 = 0.0;  ///< particle mass m, rest density rho0
    double mTime = 0.0;
    long long mTotalIterations = 0;
    std::size_t mFluid = 0;  ///< fluid particles [0, mFluid); walls after
    std::vector<double> mX, mV, mT, mQv, mQc, mRho, mP, mAcc, mAccP, mDT, mDQ;
    std::vector<double> mTheta, mVapour;  ///< T - T_e(z) and q_v - q_v,e(z), per sub-step
    std::vector<std::uint32_t> mNbr;      ///< mStride slots per fluid particle
    std::size_t mStride = 0;              ///< slots per row of mNbr and mGradF
    std::size_t mStrideHint = 48;         ///< the row width the next build starts with
    std::vector<std::uint16_t> mNbrCount;
    std::vector<float> mGradF;     ///< F_ij per neighbour slot: grad W_ij = F_ij (x_i - x_j), 1/m^5
    std::vector<double> mGradSq;   ///< |sum_j grad W_ij|^2 + sum_fluid |grad W_ij|^2 (IISPH a_ii)
    std::vector<double> mWork[7];  ///< scratch of the pressure solve, kept to avoid reallocation
    SphStepStats mStats;
};

}  // namespace cg::algo
