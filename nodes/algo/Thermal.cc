#include "nodes/algo/Thermal.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace cg::algo {

void thermalStep(const ThermalSettings& s, const ThermalArrays& in, const ThermalOutputArrays& out,
                 std::size_t begin, std::size_t end)
{
    // Single precision and restrict-qualified arrays let the compiler vectorise the loop;
    // the state is float anyway. The branches are selects, so every lane does the same work.
    const float dt = static_cast<float>(s.timeStep);
    const float accelerationPerDegree = static_cast<float>(s.buoyancyCoefficient / s.mass);
    const float gravity = static_cast<float>(s.gravity);
    const float groundTemperature = static_cast<float>(s.groundTemperature);
    const float environmentLapse = static_cast<float>(s.environmentLapse);
    const float dewPoint = static_cast<float>(s.dewPoint);
    const float dryLapse = static_cast<float>(s.dryLapse);
    const float moistLapse = static_cast<float>(s.moistLapse);
    const bool groundStops = s.groundStops;
    const float* __restrict zIn = in.z;
    const float* __restrict vzIn = in.vz;
    const float* __restrict tIn = in.temperature;
    float* __restrict zOut = out.z;
    float* __restrict vzOut = out.vz;
    float* __restrict tOut = out.temperature;
    for (std::size_t i = begin; i < end; ++i) {
        const float z = zIn[i];
        const float u = vzIn[i];
        const float t = tIn[i];
        const float environment = groundTemperature - environmentLapse * z;         // Eq. 9
        // Eq. 6 divided by m: f/m = (C_b/m)(T_v - T_e) - g
        const float acceleration = accelerationPerDegree * (t - environment) - gravity;
        float uNext = u + dt * acceleration;                                        // Eq. 7
        float zNext = z + dt * u;                                                   // Eq. 7
        const bool belowGround = groundStops && zNext < 0.0f;
        zNext = belowGround ? 0.0f : zNext;
        uNext = belowGround && uNext < 0.0f ? 0.0f : uNext;
        const float lapse = t >= dewPoint ? dryLapse : moistLapse;                  // Eq. 8
        zOut[i] = zNext;
        vzOut[i] = uNext;
        tOut[i] = t - lapse * (zNext - z);
    }
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
