#pragma once
/// The thermal step of Eq. 6-8 through a real environment (docs/atmosphere.md): the environment's
/// temperature from a sounding or the standard atmosphere instead of Eq. 9's line, each
/// particle condensing at its own lifting condensation level, the moist adiabat above it,
/// horizontal wind, and the outflow that spreads a tower's top into an anvil. Thermal.h keeps
/// the paper's step, which this one reproduces when none of that is asked for.

#include <cstddef>
#include <functional>

#include "algo/atmosphere/Column.h"
#include "algo/atmosphere/Thermal.h"

namespace cg::algo {

enum class Buoyancy {
    Paper,   ///< Eq. 6: f = C_b (T_v - T_e) - m g
    Parcel,  ///< ours: f / m = g (T_v - T_e) / T_e (kelvin), zero where T_v = T_e
};

struct ColumnThermalSettings {
    ThermalSettings paper;  ///< C_b, m, g, Delta t, the lapse rates, Eq. 9 and T_dp
    Buoyancy buoyancy = Buoyancy::Paper;
    double drag = 0.0;  ///< ours: quadratic drag, f / m -= drag |U| U, per metre
    /// The environment; its temperature tables empty for the paper's Eq. 9, its wind tables
    /// empty for calm air.
    const EnvironmentColumn* column = nullptr;
    /// With a profile: saturated particles cool at the moist adiabatic rate of their
    /// temperature and the profile's pressure instead of the fixed moist lapse.
    bool moistAdiabat = false;
    /// Outflow (ours): a saturated particle colder than its environment above this height
    /// (m above the ground) moves away from its tower's axis at divergence * distance.
    double outflowDivergence = 0.0;  ///< 1/s; 0 = no outflow
    double outflowMaxSpeed = 0.0;    ///< m/s the outflow moves a particle at most; 0 = no cap
    double outflowBottom = 0.0;      ///< m above the ground
    /// Seconds from t0 to the state being stepped, for the particles' release times.
    double time = 0.0;
};

/// What each particle brought from its emission. Its moisture: with a profile its dew point at
/// start is the profile's at its start height, and it falls kParcelDewpointLapse per metre as the
/// particle rises (a lifted parcel keeps its mixing ratio); without one it is the paper's constant
/// T_dp. `dewpointOffset`, when not null, adds each particle's own perturbation (irregular bases).
/// `releaseTime`, when not null: a particle stays at its start until that many seconds after t0.
struct ParticleStart {
    const float* startZ = nullptr;
    const float* dewpointOffset = nullptr;
    const float* releaseTime = nullptr;
};

/// The dew point of particle i at height z (m above the ground): from the column's dew point
/// when it has a profile, else the paper's `paperDewPoint`.
float particleDewpoint(const EnvironmentColumn& c, double paperDewPoint, const ParticleStart& m,
                       std::size_t i, float z);

struct ColumnState {
    const float* x;
    const float* y;
    const float* z;
    const float* vz;
    const float* temperature;
};

struct ColumnStateOut {
    float* x;
    float* y;
    float* z;
    float* vz;
    float* temperature;
    /// The horizontal velocity of this step (wind plus outflow, m/s): x, y moved by dt times
    /// it. Null where nobody reads it.
    float* vx = nullptr;
    float* vy = nullptr;
};

/// Per particle, the axis of the tower it rose in (outflow only; may be null without it).
struct TowerAxes {
    const float* x = nullptr;
    const float* y = nullptr;
};

/// Advances particles [begin, end) by Delta t, as thermalStep does (Eq. 7: position with the
/// old velocity), with T_e from the column when it has a profile, the particle's own dew point
/// choosing the lapse rate, and x, y moved by the wind at the old height (plus the outflow).
/// A particle not yet released keeps its state. Each particle is independent, so any split of
/// the range gives the same bits.
void columnThermalStep(const ColumnThermalSettings& s, const ParticleStart& m,
                       const TowerAxes& axes, const ColumnState& in, const ColumnStateOut& out,
                       std::size_t begin, std::size_t end);

/// The same step for all n particles in parallel, deterministic for any thread count.
void columnThermalStepParallel(const ColumnThermalSettings& s, const ParticleStart& m,
                               const TowerAxes& axes, const ColumnState& in,
                               const ColumnStateOut& out, std::size_t n,
                               const std::function<void()>& checkCancelled = {});

}  // namespace cg::algo
