#pragma once
/// The thermodynamics of Eq. 2 (Sec. 4), per particle, without the fluid:
///   dT/dt + (u . grad) T = alpha lap T - Gamma u_z + Q C_c               (Eq. 2)
/// The conduction term alpha lap T is the entrainment, computed between neighbours by the
/// solver (SphSolver); this file holds the local terms: the ambient air, saturation (Tetens),
/// dry adiabatic cooling, and condensation / evaporation with their latent heat.

namespace cg::algo {

struct ThermoSettings {
    double groundTemperature = 25.0;   ///< T_e at z = 0 of the ambient air, degrees C (value ours)
    double ambientLapse = 6.5e-3;      ///< -dT_e/dz of the ambient air, K/m; < Gamma = stable
                                       ///< (value ours: the standard atmosphere)
    double dryLapse = 9.8e-3;          ///< Gamma of Eq. 2, dry adiabatic lapse rate, K/m
    double latentHeat = 2.5e6;         ///< L, latent heat of condensation, J/kg
    double heatCapacity = 1005.0;      ///< c_p of dry air, J/(kg K); Q of Eq. 2 = L / c_p
    double groundPressure = 101325.0;  ///< p at z = 0, Pa
    double scaleHeight = 8400.0;       ///< H of p(z) = p0 exp(-z/H), m (value ours)
    double ambientHumidity = 0.5;      ///< relative humidity of the ambient air, 0..1 (value ours)
    double gravity = 9.81;             ///< g, m/s^2

    /// Q of Eq. 2: kelvin per (kg/kg) of water condensed.
    double latentFactor() const { return latentHeat / heatCapacity; }
};

/// T_e(z), the ambient temperature at height z (m), degrees C.
double ambientTemperature(const ThermoSettings& s, double z);
/// p(z), Pa.
double pressureAt(const ThermoSettings& s, double z);
/// Tetens: saturation vapour pressure over water at T (degrees C), Pa.
double saturationVapourPressure(double celsius);
/// Saturation specific humidity q_s(T, p), kg/kg.
double saturationHumidity(double celsius, double pressure);
/// q_v of the ambient air at height z, kg/kg (ambientHumidity times q_s(T_e(z), p(z))).
double ambientVapour(const ThermoSettings& s, double z);

/// Buoyancy acceleration of a parcel (Boussinesq, virtual temperature with water loading),
/// m/s^2: g [ (T - T_e) / (T_e + 273.15) + 0.608 (q_v - q_v,e) - q_c ].
double buoyancy(const ThermoSettings& s, double z, double temperature, double vapour,
                double condensed);

/// Moves water between vapour q_v and condensed q_c (kg/kg) towards saturation at the
/// particle's temperature and height, and releases (or absorbs) the latent heat:
/// Delta T = Q Delta q_c, with Q = L / c_p (the Q C_c term of Eq. 2 integrated over the step:
/// C_c = Delta q_c / Delta t). Supersaturation condenses (saturation adjustment, one Newton
/// step on q_s(T)); subsaturation evaporates condensed water, never more than there is.
/// Returns Delta q_c (> 0 condensation, < 0 evaporation).
double condense(const ThermoSettings& s, double z, double& temperature, double& vapour,
                double& condensed);

}  // namespace cg::algo
