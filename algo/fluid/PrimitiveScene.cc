#include "algo/fluid/PrimitiveScene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace cg::algo {

PrimitiveSettings defaultPrimitiveSettings()
{
    // Values ours, tuned by running the scene (docs/primitive.md): a bubble of warm, humid air
    // (+3 K, 95%, 250 m radius, on for the first 100 s) rises through humid (85%), stably
    // stratified air, condenses ~100 m above the source and billows into a puff that still
    // rises freely at the last frame (the box is tall enough that it never meets the lid);
    // 58,870 fluid particles at dx = 25 m.
    PrimitiveSettings s;
    s.width = 725.0;
    s.height = 1750.0;
    s.sourceHeight = 200.0;
    s.sph.spacing = 25.0;
    s.sph.cfl = 0.5;
    s.sph.thermo.ambientHumidity = 0.85;
    s.sph.maxDensityError = 0.004;
    s.sph.maxIterations = 40;
    s.sph.source.enabled = true;
    s.sph.source.radius = 250.0;
    s.sph.source.excessTemperature = 3.0;
    s.sph.source.humidity = 0.95;
    s.sph.source.relaxTime = 10.0;
    s.sph.source.duration = 100.0;
    return s;
}

std::int64_t primitiveParticleCount(const PrimitiveSettings& s)
{
    const double dx = s.sph.spacing;
    if (!(dx > 0.0)) return -1;
    const double nxy = std::round(s.width / dx), nz = std::round(s.height / dx);
    if (!(nxy >= 1.0 && nz >= 1.0) || nxy > 4096.0 || nz > 4096.0) return -1;
    return static_cast<std::int64_t>(nxy * nxy * nz);
}

PrimitiveResult simulatePrimitive(const PrimitiveSettings& s, const std::function<void()>& poll,
                                  const std::function<void(int)>& progress)
{
    const std::int64_t n = primitiveParticleCount(s);
    if (n < 1 || n > s.maxParticles)
        throw std::invalid_argument("PrimitiveSim: the box needs " + std::to_string(n) +
                                    " particles (allowed 1.." + std::to_string(s.maxParticles) +
                                    ")");
    if (s.frames < 1) throw std::invalid_argument("PrimitiveSim: frames must be >= 1");
    if (!(s.frameTime > 0.0))
        throw std::invalid_argument("PrimitiveSim: frame time must be positive");

    SphSettings sph = s.sph;
    const double lo[3] = {-0.5 * s.width, -0.5 * s.width, 0.0};
    const double hi[3] = {0.5 * s.width, 0.5 * s.width, s.height};
    sph.source.centre[0] = 0.0;
    sph.source.centre[1] = 0.0;
    sph.source.centre[2] = s.sourceHeight;
    SphSolver solver(sph, lo, hi);

    PrimitiveResult out;
    out.frameTime = s.frameTime;
    out.fluidParticles = solver.size();
    std::vector<std::uint32_t> cloud;  // fluid index of each cloud id
    std::vector<unsigned char> inCloud(solver.size(), 0);
    // The cloud origin: where the cloud first appears (the first cloud particles' mean x and y
    // at their lowest z). Positions are stored relative to it, so a mapped copy grows from its
    // source particle upwards instead of floating a condensation level above it.
    bool anchored = false;
    for (int f = 0; f < s.frames; ++f) {
        if (f > 0) {
            out.subSteps += solver.advance(s.frameTime, poll);
            out.maxDensityError = std::max(out.maxDensityError, solver.lastStats().maxDensityError);
            out.meanDensityError =
                std::max(out.meanDensityError, solver.lastStats().meanDensityError);
        }
        // New cloud particles join in index order, so ids do not depend on threads.
        const std::vector<double>& qc = solver.condensed();
        for (std::size_t i = 0; i < solver.size(); ++i)
            if (!inCloud[i] && qc[i] > s.cloudThreshold) {
                inCloud[i] = 1;
                cloud.push_back(static_cast<std::uint32_t>(i));
            }
        out.counts.push_back(static_cast<std::uint32_t>(cloud.size()));
        const std::vector<double>& x = solver.positions();
        if (!anchored && !cloud.empty()) {
            out.origin[2] = x[3 * std::size_t{cloud[0]} + 2];
            for (std::uint32_t i : cloud) {
                out.origin[0] += x[3 * std::size_t{i}] / static_cast<double>(cloud.size());
                out.origin[1] += x[3 * std::size_t{i} + 1] / static_cast<double>(cloud.size());
                out.origin[2] = std::min(out.origin[2], x[3 * std::size_t{i} + 2]);
            }
            anchored = true;
        }
        for (std::uint32_t i : cloud)
            for (int a = 0; a < 3; ++a)
                out.positions.push_back(
                    static_cast<float>(x[3 * std::size_t{i} + a] - out.origin[a]));
        if (progress) progress(f);
    }
    out.pressureIterations = solver.totalPressureIterations();
    return out;
}

}  // namespace cg::algo
