#pragma once
/// The rising of water vapour particles under the thermal effect (Sec. 5.1, Eq. 6-9): one
/// explicit Euler step per call, exactly as the paper writes it.

#include <cstddef>
#include <functional>

namespace cg::algo {

struct ThermalSettings {
    double buoyancyCoefficient = 2.0;  ///< C_b of Eq. 6, newtons per degree C
    double mass = 1.0;                 ///< m of Eq. 6-7, kg
    double gravity = 9.81;             ///< g of Eq. 6, m/s^2
    double groundTemperature = 20.0;   ///< T_sl_max of Eq. 9, degrees C
    double environmentLapse = 6.4e-3;  ///< C_e of Eq. 9, degrees C per metre
    double dewPoint = 16.0;            ///< T_dp of Eq. 8, degrees C
    double dryLapse = 10.0e-3;         ///< C of Eq. 8 while T_v >= T_dp, degrees C per metre
    double moistLapse = 6.0e-3;        ///< C of Eq. 8 once T_v < T_dp, degrees C per metre
    double timeStep = 0.2;             ///< Delta t of Eq. 7-8, seconds
    /// Ours, not the paper's: a particle cannot sink below the ground (z = 0); it stops there.
    bool groundStops = true;
};

/// Arrays of one state: height P_vz (m), vertical velocity U_vz (m/s), temperature T_v (C).
struct ThermalArrays {
    const float* z;
    const float* vz;
    const float* temperature;
};

struct ThermalOutputArrays {
    float* z;
    float* vz;
    float* temperature;
};

/// Advances particles [begin, end) from t to t + Delta t:
///   T_e(t)    = T_sl_max - C_e P_vz(t)                          (Eq. 9)
///   f(t)      = C_b (T_v(t) - T_e(t)) - m g                      (Eq. 6)
///   U(t+dt)   = U(t) + dt f(t) / m                               (Eq. 7)
///   P(t+dt)   = P(t) + dt U(t)                                   (Eq. 7, velocity of time t)
///   T_v(t+dt) = T_v(t) - C (P(t+dt) - P(t)), C = dry if T_v(t) >= T_dp else moist   (Eq. 8)
/// Arithmetic is in single precision, like the state; each particle is independent, so any
/// split of the range gives the same bits.
void thermalStep(const ThermalSettings& s, const ThermalArrays& in, const ThermalOutputArrays& out,
                 std::size_t begin, std::size_t end);

/// The same step for all n particles, in parallel (TBB), deterministic for any thread count.
/// `checkCancelled` is called between blocks.
void thermalStepParallel(const ThermalSettings& s, const ThermalArrays& in,
                         const ThermalOutputArrays& out, std::size_t n,
                         const std::function<void()>& checkCancelled = {});

}  // namespace cg::algo
