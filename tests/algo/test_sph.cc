// Physics of the SPH solver (algo/fluid/Sph*): kernel, neighbour search, rest, buoyancy,
// conduction, adiabatic cooling and latent heat.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "algo/fluid/SphGrid.h"
#include "algo/fluid/SphKernel.h"
#include "algo/fluid/SphSolver.h"
#include "algo/fluid/SphThermo.h"

namespace cg::algo {

TEST(SphKernel, IntegratesToOneAndGradientIsAntisymmetric)
{
    const SphKernel k(2.0);
    const double d = 0.05;
    double sum = 0.0;
    for (double x = -2.0 + d / 2; x < 2.0; x += d)
        for (double y = -2.0 + d / 2; y < 2.0; y += d)
            for (double z = -2.0 + d / 2; z < 2.0; z += d)
                sum += k.value(std::sqrt(x * x + y * y + z * z));
    EXPECT_NEAR(sum * d * d * d, 1.0, 2e-3);
    const double x[3] = {0.3, -0.7, 0.4}, mx[3] = {-0.3, 0.7, -0.4};
    const double r = std::sqrt(0.09 + 0.49 + 0.16);
    double g[3], mg[3];
    k.gradient(x, r, g);
    k.gradient(mx, r, mg);
    for (int a = 0; a < 3; ++a) EXPECT_EQ(g[a], -mg[a]);
    EXPECT_LT(k.derivative(r), 0.0);
    EXPECT_EQ(k.value(2.0), 0.0);
}

TEST(SphGrid, NeighboursEqualBruteForceInCellThenIndexOrder)
{
    // Some points lie outside the box (clamped into its border cells); radii up to the cell.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 11.0);
    std::vector<double> x(3 * 2000);
    for (double& v : x) v = u(rng);
    const double lo[3] = {0, 0, 0}, hi[3] = {10, 10, 10};
    SphGrid grid(lo, hi, 1.3);
    grid.build(x.data(), 2000);
    for (const double radius : {1.3, 0.9}) {
        for (std::size_t i = 0; i < 2000; i += 7) {
            std::vector<std::uint32_t> fast;
            grid.forEachNeighbour(&x[3 * i], radius, [&](std::uint32_t j) { fast.push_back(j); });
            std::vector<std::pair<std::size_t, std::uint32_t>> brute;  // (cell, index)
            for (std::uint32_t j = 0; j < 2000; ++j) {
                const double dx = x[3 * j] - x[3 * i], dy = x[3 * j + 1] - x[3 * i + 1],
                             dz = x[3 * j + 2] - x[3 * i + 2];
                if (dx * dx + dy * dy + dz * dz < radius * radius)
                    brute.emplace_back(grid.cellIndex(&x[3 * j]), j);
            }
            std::sort(brute.begin(), brute.end());
            std::vector<std::uint32_t> expected;
            for (const auto& b : brute) expected.push_back(b.second);
            EXPECT_EQ(fast, expected) << "particle " << i << ", radius " << radius;
        }
    }
}

namespace {
SphSettings calmSettings()
{
    SphSettings s;
    s.spacing = 10.0;
    s.thermo.ambientHumidity = 0.3;
    return s;
}
}  // namespace

TEST(SphSolver, RestingBoxStaysAtRest)
{
    const double lo[3] = {0, 0, 0}, hi[3] = {80, 80, 80};
    SphSolver solver(calmSettings(), lo, hi);
    double worst = 0.0, fastest = 0.0;
    for (int k = 0; k < 1000; ++k) {
        solver.step(1.0);
        worst = std::max(worst, solver.lastStats().maxDensityError);
        fastest = std::max(fastest, solver.lastStats().maxSpeed);
    }
    EXPECT_LT(worst, 0.01);
    EXPECT_LT(fastest, 1e-6);
}

TEST(SphSolver, WarmBlobRisesColdBlobSinks)
{
    const double lo[3] = {0, 0, 0}, hi[3] = {120, 60, 160};
    SphSettings s = calmSettings();
    s.thermodynamics = false;
    SphSolver solver(s, lo, hi);
    const std::vector<double>& x = solver.positions();
    std::vector<std::size_t> warm, cold;
    for (std::size_t i = 0; i < solver.size(); ++i) {
        const double dx = x[3 * i] - 30, dy = x[3 * i + 1] - 30, dzw = x[3 * i + 2] - 50,
                     dzc = x[3 * i + 2] - 110;
        const double dxc = x[3 * i] - 90;
        if (dx * dx + dy * dy + dzw * dzw < 20 * 20) {
            warm.push_back(i);
            solver.temperatures()[i] += 3.0;
        } else if (dxc * dxc + dy * dy + dzc * dzc < 20 * 20) {
            cold.push_back(i);
            solver.temperatures()[i] -= 3.0;
        }
    }
    auto meanZ = [&](const std::vector<std::size_t>& set) {
        double z = 0;
        for (std::size_t i : set) z += solver.positions()[3 * i + 2];
        return z / static_cast<double>(set.size());
    };
    const double warm0 = meanZ(warm), cold0 = meanZ(cold);
    solver.advance(30.0);
    EXPECT_GT(meanZ(warm), warm0 + 2.0);
    EXPECT_LT(meanZ(cold), cold0 - 2.0);
    // The pressure solve meets its target on the predicted density (max 0.2%, mean ~0.04%).
    EXPECT_LT(solver.lastStats().solverDensityError, s.maxDensityError);
    EXPECT_LT(solver.lastStats().meanDensityError, 0.001);
    // KNOWN LIMIT (docs/primitive.md): the true density of the moved particles differs from
    // the prediction at second order in the step, most next to the walls: 1.5% here.
    EXPECT_LT(solver.lastStats().maxDensityError, 0.02);
}

TEST(SphSolver, ConductionAloneConservesHeat)
{
    const double lo[3] = {0, 0, 0}, hi[3] = {60, 60, 60};
    SphSettings s = calmSettings();
    s.buoyancy = false;
    s.thermodynamics = false;
    s.thermo.ambientLapse = 0.0;
    s.conduction = 20.0;
    SphSolver solver(s, lo, hi);
    for (std::size_t i = 0; i < solver.size(); i += 5) solver.temperatures()[i] += 4.0;
    const double before = solver.totalTemperature();
    double spreadBefore = 0, spreadAfter = 0;
    for (double t : solver.temperatures()) spreadBefore = std::max(spreadBefore, t);
    for (int k = 0; k < 50; ++k) solver.step(0.5);
    for (double t : solver.temperatures()) spreadAfter = std::max(spreadAfter, t);
    EXPECT_NEAR(solver.totalTemperature(), before, 1e-10 * std::fabs(before));
    EXPECT_LT(spreadAfter, spreadBefore - 1.0);  // it did conduct
}

TEST(SphSolver, LiftedParticleCoolsAtTheDryLapseRate)
{
    // A 2 x 1 x 100 box of dry air, no buoyancy: one column of particles rises, the other
    // sinks (a closed box cannot lift everything), so the flow is divergence-free.
    const double lo[3] = {0, 0, 0}, hi[3] = {20, 10, 1000};
    SphSettings s;
    s.spacing = 10.0;
    s.buoyancy = false;
    s.thermo.ambientHumidity = 0.0;
    s.conduction = 0.0;
    s.viscosity = 0.0;
    SphSolver solver(s, lo, hi);
    for (std::size_t i = 0; i < solver.size(); ++i)
        solver.velocities()[3 * i + 2] = solver.positions()[3 * i] < 10.0 ? 2.0 : -2.0;
    const std::size_t i = 20;  // the rising column (x = 5 m), 10th layer from the floor
    const double z0 = solver.positions()[3 * i + 2], t0 = solver.temperatures()[i];
    for (int k = 0; k < 20; ++k) solver.step(1.0);
    const double dz = solver.positions()[3 * i + 2] - z0;
    EXPECT_GT(dz, 10.0);
    EXPECT_NEAR(solver.temperatures()[i] - t0, -s.thermo.dryLapse * dz, 1e-9);
    EXPECT_EQ(solver.condensed()[i], 0.0);
}

TEST(SphThermo, CondensationReleasesLatentHeat)
{
    ThermoSettings s;
    double t = 10.0, qc = 0.0;
    const double qs = saturationHumidity(t, pressureAt(s, 500.0));
    double qv = qs + 0.002;  // supersaturated
    const double t0 = t;
    const double dq = condense(s, 500.0, t, qv, qc);
    EXPECT_GT(dq, 0.0);
    EXPECT_NEAR(qc, dq, 1e-15);
    EXPECT_NEAR(t - t0, s.latentHeat / s.heatCapacity * dq, 1e-9);
    // After the adjustment the parcel is (nearly) saturated at its new temperature.
    EXPECT_NEAR(qv, saturationHumidity(t, pressureAt(s, 500.0)), 1e-7);
    // Drier air evaporates it back, never more than there is.
    double qv2 = 0.0;
    const double dq2 = condense(s, 500.0, t, qv2, qc);
    EXPECT_LT(dq2, 0.0);
    EXPECT_GE(qc, 0.0);
}

TEST(SphThermo, TetensAtKnownPoints)
{
    EXPECT_NEAR(saturationVapourPressure(0.0), 610.78, 1e-9);
    EXPECT_NEAR(saturationVapourPressure(20.0), 2338.0, 5.0);  // tables: 2339 Pa
}

}  // namespace cg::algo
