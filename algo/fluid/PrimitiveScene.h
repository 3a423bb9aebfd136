#pragma once
/// The scene of the 3D cloud primitive set (Sec. 4, Figure 2): still, stably stratified air in
/// a closed box and a warm, moist source near the floor. The source feeds a rising thermal
/// that cools adiabatically, condenses above its lifting condensation level, releases latent
/// heat and billows into a cauliflower-topped cumulus puff. The cloud particles are the fluid
/// particles that have condensed: ids in order of appearance, N_f(s) never decreasing,
/// positions relative to the cloud origin (where the cloud first appears).

#include <cstdint>
#include <functional>
#include <vector>

#include "algo/fluid/SphSolver.h"

namespace cg::algo {

struct PrimitiveSettings {
    SphSettings sph;               ///< the fluid and thermodynamics (see SphSettings)
    double width = 500.0;          ///< box edge along x and y, m (value ours)
    double height = 800.0;         ///< box height along z, m (value ours)
    double sourceHeight = 100.0;   ///< height of the source centre above the floor, m (ours)
    int frames = 150;              ///< primitive frames s = 0..frames-1 (paper: 154 steps)
    double frameTime = 2.0;        ///< Delta s, seconds of physical time per frame (ours)
    double cloudThreshold = 1e-5;  ///< q_c above which a particle is a cloud particle, kg/kg
    int maxParticles = 4000000;    ///< refuse boxes that would need more fluid particles
};

/// The default settings (PrimitiveSim's defaults): 58,870 fluid particles, 150 frames of 2 s
/// (see docs/primitive.md for what they give).
PrimitiveSettings defaultPrimitiveSettings();

struct PrimitiveResult {
    double frameTime = 0.0;             ///< Delta s, seconds
    std::vector<std::uint32_t> counts;  ///< N_f(s)
    std::vector<float> positions;       ///< xyz per cloud particle per frame, m from origin
    /// The cloud origin in box coordinates (m): the first cloud particles' mean x and y at
    /// their lowest z; (0, 0, 0) when nothing condenses.
    double origin[3] = {0.0, 0.0, 0.0};
    std::size_t fluidParticles = 0;    ///< fluid particles simulated
    long long subSteps = 0;            ///< CFL sub-steps taken in all
    long long pressureIterations = 0;  ///< pressure-solve iterations in all
    double maxDensityError = 0.0;      ///< largest max |rho - rho0| / rho0 over the run
    double meanDensityError = 0.0;     ///< largest mean solver error over the run
};

/// Fluid particles the box of `s` needs (for allocation checks), without building anything.
std::int64_t primitiveParticleCount(const PrimitiveSettings& s);

/// Runs the scene. `poll` is called between sub-steps (it may throw to cancel); `progress`,
/// when set, gets each finished frame.
PrimitiveResult simulatePrimitive(const PrimitiveSettings& s,
                                  const std::function<void()>& poll = {},
                                  const std::function<void(int)>& progress = {});

}  // namespace cg::algo
