// The thermal rise of Eq. 6-9, checked against the recurrence written out independently.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <tbb/global_control.h>

#include "algo/atmosphere/Thermal.h"

namespace cg::algo {

namespace {

struct Particle {
    float z, vz, t;
};

Particle step(const ThermalSettings& s, Particle p)
{
    std::vector<float> z{p.z}, vz{p.vz}, t{p.t}, z2(1), vz2(1), t2(1);
    thermalStep(s, {z.data(), vz.data(), t.data()}, {z2.data(), vz2.data(), t2.data()}, 0, 1);
    return {z2[0], vz2[0], t2[0]};
}

/// Eq. 6-9 as the paper prints them, in double, rounded to the float state after each step.
Particle referenceStep(const ThermalSettings& s, Particle p)
{
    const double te = s.groundTemperature - s.environmentLapse * p.z;          // Eq. 9
    const double f = s.buoyancyCoefficient * (p.t - te) - s.mass * s.gravity;  // Eq. 6
    const double u = p.vz + s.timeStep * f / s.mass;                           // Eq. 7
    const double z = p.z + s.timeStep * p.vz;                                  // Eq. 7
    const double c = p.t >= s.dewPoint ? 10.0e-3 : 6.0e-3;                     // Eq. 8
    const double t = p.t - c * (z - p.z);
    return {static_cast<float>(z), static_cast<float>(u), static_cast<float>(t)};
}

}  // namespace

TEST(Thermal, TrajectoryFollowsTheRecurrenceStepByStep)
{
    ThermalSettings s;
    Particle p{50.0f, 0.0f, 29.5f};
    Particle ref = p;
    auto near = [](float a, float b, double rel) {
        return std::abs(static_cast<double>(a) - b) <=
               rel * std::max(1.0, std::abs(static_cast<double>(b)));
    };
    for (int n = 0; n < 400; ++n) {
        // Each step, from the same state, agrees with the paper's formulas to float precision.
        const Particle expected = referenceStep(s, p);
        const Particle next = step(s, p);
        ASSERT_TRUE(near(next.z, expected.z, 1e-6))
            << "step " << n << ": " << next.z << " vs " << expected.z;
        ASSERT_TRUE(near(next.vz, expected.vz, 1e-6)) << "step " << n;
        // T_v moves by C dz, and dz is a difference of float heights: allow their rounding.
        ASSERT_TRUE(near(next.t, expected.t, 1e-5)) << "step " << n;
        p = next;
        // And the whole trajectory stays on the reference one (rounding only accumulates).
        ref = referenceStep(s, ref);
        ASSERT_TRUE(near(p.z, ref.z, 1e-4)) << "step " << n;
        ASSERT_TRUE(near(p.t, ref.t, 1e-3)) << "step " << n;
    }
    EXPECT_GT(p.z, 3000.0f);  // it rose through the cloud base and kept rising
}

TEST(Thermal, PositionAdvancesWithTheVelocityOfTimeT)
{
    ThermalSettings s;
    const Particle p = step(s, {100.0f, 5.0f, 30.0f});
    EXPECT_FLOAT_EQ(p.z, 100.0f + 0.2f * 5.0f);  // not the updated velocity
    const double force = s.buoyancyCoefficient * (30.0 - (20.0 - 6.4e-3 * 100.0)) - 9.81;
    EXPECT_FLOAT_EQ(p.vz, static_cast<float>(5.0 + 0.2 * force));
}

TEST(Thermal, CondensesWithinOneStepOfTheClosedFormAltitude)
{
    ThermalSettings s;
    for (const Particle start : {Particle{0.0f, 0.0f, 30.0f}, Particle{100.0f, 0.0f, 29.0f},
                                 Particle{37.0f, 0.0f, 29.63f}}) {
        const double closedForm = start.z + (start.t - s.dewPoint) / 10.0e-3;
        Particle p = start;
        Particle before = p;
        int steps = 0;
        while (p.t >= s.dewPoint && steps < 10000) {
            before = p;
            p = step(s, p);
            ++steps;
        }
        ASSERT_LT(steps, 10000);
        // The first state below T_dp lies within one step's travel above the altitude.
        EXPECT_GE(p.z + 1e-2, closedForm);
        EXPECT_LE(p.z - (p.z - before.z), closedForm + 1e-2);
    }
}

TEST(Thermal, LapseRateSwitchesAtTheDewPoint)
{
    ThermalSettings s;
    Particle p{0.0f, 0.0f, 30.0f};
    int dry = 0, moist = 0;
    for (int n = 0; n < 300; ++n) {
        const Particle next = step(s, p);
        const double dz = static_cast<double>(next.z) - p.z;
        if (std::abs(dz) > 1.0) {
            const double rate = -(static_cast<double>(next.t) - p.t) / dz;
            if (p.t >= s.dewPoint) {
                EXPECT_NEAR(rate, 10.0e-3, 2e-5) << "step " << n;
                ++dry;
            } else {
                EXPECT_NEAR(rate, 6.0e-3, 2e-5) << "step " << n;
                ++moist;
            }
        }
        p = next;
    }
    EXPECT_GT(dry, 10);
    EXPECT_GT(moist, 10);
}

TEST(Thermal, NegativeBuoyancyDecelerates)
{
    ThermalSettings s;
    // Colder than its environment: f = C_b (T_v - T_e) - m g < 0.
    Particle p{1000.0f, 20.0f, 5.0f};
    for (int n = 0; n < 20; ++n) {
        const Particle next = step(s, p);
        EXPECT_LT(next.vz, p.vz) << "step " << n;
        p = next;
    }
}

TEST(Thermal, GroundStopsASinkingParticleOnlyWhenAsked)
{
    ThermalSettings s;
    const Particle sinking{1.0f, -20.0f, 0.0f};
    const Particle stopped = step(s, sinking);
    EXPECT_EQ(stopped.z, 0.0f);
    EXPECT_EQ(stopped.vz, 0.0f);
    s.groundStops = false;
    EXPECT_LT(step(s, sinking).z, 0.0f);
}

TEST(Thermal, ParallelStepIsBitIdenticalForOneAndTwoThreads)
{
    const std::size_t n = 200000;
    std::vector<float> z(n), vz(n), t(n);
    for (std::size_t i = 0; i < n; ++i) {
        z[i] = static_cast<float>(i % 1000);
        vz[i] = static_cast<float>(i % 7) - 3.0f;
        t[i] = 15.0f + static_cast<float>(i % 150) * 0.1f;
    }
    ThermalSettings s;
    std::vector<std::vector<float>> results;
    for (int threads : {1, 2}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        std::vector<float> z2(n), vz2(n), t2(n);
        thermalStepParallel(s, {z.data(), vz.data(), t.data()}, {z2.data(), vz2.data(), t2.data()},
                            n);
        z2.insert(z2.end(), vz2.begin(), vz2.end());
        z2.insert(z2.end(), t2.begin(), t2.end());
        results.push_back(std::move(z2));
    }
    EXPECT_EQ(results[0], results[1]);
}

}  // namespace cg::algo
