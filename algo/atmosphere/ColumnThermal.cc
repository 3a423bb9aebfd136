#include "algo/atmosphere/ColumnThermal.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "algo/atmosphere/Thermodynamics.h"

namespace cg::algo {

float particleDewpoint(const EnvironmentColumn& c, double paperDewPoint, const ParticleStart& m,
                       std::size_t i, float z)
{
    const float offset = m.dewpointOffset ? m.dewpointOffset[i] : 0.0f;
    if (c.temperature.empty()) return static_cast<float>(paperDewPoint) + offset;
    const float z0 = m.startZ[i];
    return c.at(c.dewpoint, z0) - static_cast<float>(thermo::kParcelDewpointLapse) * (z - z0) +
           offset;
}

void columnThermalStep(const ColumnThermalSettings& s, const ParticleStart& m,
                       const TowerAxes& axes, const ColumnState& in, const ColumnStateOut& out,
                       std::size_t begin, std::size_t end)
{
    const ThermalSettings& p = s.paper;
    const EnvironmentColumn& c = *s.column;
    const bool profile = !c.temperature.empty();
    const bool windy = !c.windEast.empty();
    const bool outflow = s.outflowDivergence > 0.0 && axes.x && axes.y;
    const float dt = static_cast<float>(p.timeStep);
    const float accelerationPerDegree = static_cast<float>(p.buoyancyCoefficient / p.mass);
    const float gravity = static_cast<float>(p.gravity);
    const float drag = static_cast<float>(s.drag);
    const float kelvin = static_cast<float>(thermo::kKelvin);
    const float divergence = static_cast<float>(s.outflowDivergence);
    const float outflowBottom = static_cast<float>(s.outflowBottom);
    const float maxSpeed = static_cast<float>(s.outflowMaxSpeed);
    const float floorHeight = p.groundStops ? 0.0f : -std::numeric_limits<float>::infinity();
    const float time = static_cast<float>(s.time);
    for (std::size_t i = begin; i < end; ++i) {
        if (m.releaseTime && m.releaseTime[i] > time) {  // still waiting at its start
            out.x[i] = in.x[i];
            out.y[i] = in.y[i];
            out.z[i] = in.z[i];
            out.vz[i] = in.vz[i];
            out.temperature[i] = in.temperature[i];
            if (out.vx != nullptr) out.vx[i] = out.vy[i] = 0.0f;
            continue;
        }
        const float z = in.z[i];
        const float u = in.vz[i];
        const float t = in.temperature[i];
        const float environment = profile
                                      ? c.at(c.temperature, z)
                                      : static_cast<float>(p.groundTemperature) -
                                            static_cast<float>(p.environmentLapse) * z;  // Eq. 9
        float acceleration = s.buoyancy == Buoyancy::Paper
                                 ? accelerationPerDegree * (t - environment) - gravity  // Eq. 6
                                 : gravity * (t - environment) / (environment + kelvin);
        acceleration -= drag * std::fabs(u) * u;
        float uNext = u + dt * acceleration;  // Eq. 7
        float zNext = z + dt * u;
        const bool belowGround = zNext < floorHeight;
        zNext = belowGround ? floorHeight : zNext;
        uNext = belowGround ? std::max(uNext, 0.0f) : uNext;
        const bool saturated = t < particleDewpoint(c, p.dewPoint, m, i, z);
        const float moist =
            s.moistAdiabat && profile
                ? static_cast<float>(thermo::moistAdiabaticLapse(t, c.at(c.pressure, z)))
                : static_cast<float>(p.moistLapse);
        const float lapse = saturated ? moist : static_cast<float>(p.dryLapse);  // Eq. 8
        out.z[i] = zNext;
        out.vz[i] = uNext;
        out.temperature[i] = t - lapse * (zNext - z);

        float vx = windy ? c.at(c.windEast, z) : 0.0f;
        float vy = windy ? c.at(c.windNorth, z) : 0.0f;
        if (outflow && saturated && t < environment && z >= outflowBottom) {
            float ox = divergence * (in.x[i] - axes.x[i]), oy = divergence * (in.y[i] - axes.y[i]);
            const float speed = std::hypot(ox, oy);
            if (maxSpeed > 0.0f && speed > maxSpeed) {  // a gravity current's speed, not more
                ox *= maxSpeed / speed;
                oy *= maxSpeed / speed;
            }
            vx += ox;
            vy += oy;
        }
        out.x[i] = in.x[i] + dt * vx;
        out.y[i] = in.y[i] + dt * vy;
        if (out.vx != nullptr) out.vx[i] = vx, out.vy[i] = vy;
    }
}

void columnThermalStepParallel(const ColumnThermalSettings& s, const ParticleStart& m,
                               const TowerAxes& axes, const ColumnState& in,
                               const ColumnStateOut& out, std::size_t n,
                               const std::function<void()>& checkCancelled)
{
    constexpr std::size_t kGrain = 16384;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          if (checkCancelled) checkCancelled();
                          columnThermalStep(s, m, axes, in, out, r.begin(), r.end());
                      });
}

}  // namespace cg::algo
