#include "algo/atmosphere/Thermal.h"

#include <algorithm>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace cg::algo {

namespace {

/// Eq. 6-9 in single precision, on restrict-qualified arrays so the compiler vectorises the
/// loop (the state is float anyway). The branches are selects: every lane does the same work.
void stepKernel(const float* __restrict zIn, const float* __restrict vzIn,
                const float* __restrict tIn, float* __restrict zOut, float* __restrict vzOut,
                float* __restrict tOut, std::size_t begin, std::size_t end,
                const ThermalSettings& s)
{
    const float dt = static_cast<float>(s.timeStep);
    const float accelerationPerDegree = static_cast<float>(s.buoyancyCoefficient / s.mass);
    const float gravity = static_cast<float>(s.gravity);
    const float groundTemperature = static_cast<float>(s.groundTemperature);
    const float environmentLapse = static_cast<float>(s.environmentLapse);
    const float dewPoint = static_cast<float>(s.dewPoint);
    const float dryLapse = static_cast<float>(s.dryLapse);
    const float moistLapse = static_cast<float>(s.moistLapse);
    // Without a ground, no height is below the floor.
    const float floorHeight = s.groundStops ? 0.0f : -std::numeric_limits<float>::infinity();
    for (std::size_t i = begin; i < end; ++i) {
        const float z = zIn[i];
        const float u = vzIn[i];
        const float t = tIn[i];
        const float environment = groundTemperature - environmentLapse * z;  // Eq. 9
        // Eq. 6 divided by m: f/m = (C_b/m)(T_v - T_e) - g
        const float acceleration = accelerationPerDegree * (t - environment) - gravity;
        float uNext = u + dt * acceleration;  // Eq. 7
        float zNext = z + dt * u;             // Eq. 7
        const bool belowGround = zNext < floorHeight;
        zNext = belowGround ? floorHeight : zNext;
        uNext = belowGround ? std::max(uNext, 0.0f) : uNext;
        const float lapse = t >= dewPoint ? dryLapse : moistLapse;  // Eq. 8
        zOut[i] = zNext;
        vzOut[i] = uNext;
        tOut[i] = t - lapse * (zNext - z);
    }
}

}  // namespace

void thermalStep(const ThermalSettings& s, const ThermalArrays& in, const ThermalOutputArrays& out,
                 std::size_t begin, std::size_t end)
{
    stepKernel(in.z, in.vz, in.temperature, out.z, out.vz, out.temperature, begin, end, s);
}

void thermalStepParallel(const ThermalSettings& s, const ThermalArrays& in,
                         const ThermalOutputArrays& out, std::size_t n,
                         const std::function<void()>& checkCancelled)
{
    constexpr std::size_t kGrain = 16384;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          if (checkCancelled) checkCancelled();
                          thermalStep(s, in, out, r.begin(), r.end());
                      });
}

}  // namespace cg::algo
