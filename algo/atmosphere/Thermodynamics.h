#pragma once
/// Moist-air thermodynamics for real atmospheres (the paper's Eq. 8-9 use fixed
/// lapse rates instead). Temperatures in degrees C, pressures in hPa, heights in metres.
/// The formulas are the textbook ones (Bolton 1980 for saturation; the saturated-adiabatic
/// lapse rate of the AMS Glossary); the constants are the usual dry-air and water values.

namespace cg::algo::thermo {

constexpr double kGravity = 9.80665;         ///< standard gravity, m/s^2 (ICAO)
constexpr double kDryGasConstant = 287.053;  ///< R_d, J/(kg K) (ICAO)
constexpr double kDryHeatCapacity = 1005.0;  ///< c_pd, J/(kg K)
constexpr double kLatentHeat = 2.501e6;      ///< L_v at 0 C, J/kg
constexpr double kMolarMassRatio = 0.622;    ///< epsilon = R_d / R_v
constexpr double kKelvin = 273.15;
/// Gamma_d = g / c_pd: a dry parcel cools 9.76 C per km.
constexpr double kDryAdiabaticLapse = kGravity / kDryHeatCapacity;
/// An unsaturated parcel keeps its mixing ratio, so its dew point falls about 1.8 C per km;
/// with the dry lapse it meets the temperature 125 m higher per C of dew-point depression.
constexpr double kParcelDewpointLapse = 1.8e-3;

/// Saturation vapour pressure over water, hPa (Bolton 1980: 0.1% from -30 to 35 C).
double saturationVapourPressure(double temperatureC);

/// Saturation mixing ratio r_s = epsilon e_s / (p - e_s), kg/kg.
double saturationMixingRatio(double temperatureC, double pressureHPa);

/// Gamma_m = g (1 + L r_s / (R_d T)) / (c_pd + L^2 r_s epsilon / (R_d T^2)), C per metre: how
/// fast a saturated parcel cools as it rises (about 4 C/km in warm moist air near the ground,
/// approaching the dry 9.8 C/km in the cold upper troposphere).
double moistAdiabaticLapse(double temperatureC, double pressureHPa);

/// The pressure at the top of a layer of depth dz (m) whose bottom has pressure p0 (hPa) and
/// temperatures t0, t1 (C) at its bottom and top: hydrostatic with the layer's mean
/// temperature, p0 exp(-g dz / (R_d T_mean)).
double hydrostaticPressure(double p0HPa, double t0C, double t1C, double dz);

}  // namespace cg::algo::thermo
