#pragma once
/// The liquid water a cumulus holds and the optics that follow from it (ours: the paper's
/// clouds have no water content; cloud physics gives it).
///
/// Water: a parcel saturated at the cloud base rises along the moist (pseudo-)adiabat; what it
/// can no longer hold as vapour condenses. The adiabatic liquid water content at height h
/// above the base is LWC_ad(h) = rho_d (r_s(base) - r_s(T(h), p(h))), with T cooling at the
/// saturated-adiabatic lapse rate thermo::moistAdiabaticLapse and p hydrostatic (real gravity,
/// whatever the simulation's buoyancy uses): about 2 g/m^3 per km near a warm base, less in
/// the cold upper troposphere. Real cumulus hold a fraction of it, 30-80%, the rest lost to
/// the dry air they entrain (Warner 1970; Pruppacher and Klett 1997, ch. 2).
///
/// Optics (geometric optics, droplets much larger than the wavelength): a volume of droplets
/// of effective radius r_eff holding LWC has extinction sigma = 3 LWC / (2 rho_w r_eff)
/// (Stephens 1978), and r_eff follows from LWC and the droplet number concentration N as
/// r_eff = (3 LWC / (4 pi rho_w k N))^(1/3), k the ratio of the volume-mean to the effective
/// radius cubed: 0.67 in continental and 0.80 in maritime air (Martin, Johnson and Spice
/// 1994). So sigma grows as LWC^(2/3) N^(1/3): 1 g/m^3 of continental cloud (N = 500 /cm^3)
/// has sigma 0.17 /m, a mean free path of 6 m.

#include <vector>

namespace cg::algo {

inline constexpr double kWaterDensity = 1000.0;  ///< rho_w, kg/m^3

/// LWC_ad(h) of a parcel saturated at temperature baseTemperatureC and pressure
/// basePressureHPa, tabulated every `step` metres up to `depth` above the base.
class AdiabaticWater {
public:
    AdiabaticWater(double baseTemperatureC, double basePressureHPa, double depth = 16000.0,
                   double step = 10.0);
    /// g/m^3 at h metres above the base: 0 at and below it, linear between the table's
    /// heights, the top's value above its depth.
    double at(double h) const;
    /// The parcel's temperature (C) at h metres above the base.
    double temperature(double h) const;

private:
    double mStep;
    std::vector<double> mWater;        ///< g/m^3 at i * step
    std::vector<double> mTemperature;  ///< C at i * step
    static double lookup(const std::vector<double>& table, double h, double step);
};

/// Droplets of a cloud: how many, and how their sizes spread.
struct DropletPopulation {
    double concentrationPerCm3 = 500.0;  ///< N
    double k = 0.67;                     ///< (r_volume / r_eff)^3
};

inline constexpr DropletPopulation kContinentalDroplets{500.0, 0.67};
inline constexpr DropletPopulation kMaritimeDroplets{100.0, 0.80};

/// r_eff in metres for LWC in g/m^3 (0 for no water).
double effectiveRadius(double lwcGramsPerM3, const DropletPopulation& droplets);

/// sigma in 1/m for LWC in g/m^3.
double extinctionFromWater(double lwcGramsPerM3, const DropletPopulation& droplets);

/// The asymmetry parameter g of the droplets' phase function at visible wavelengths, for an
/// effective radius in metres: 0.87 - 0.07 exp(-r_eff / 4 um), a fit of ours through the
/// values Mie theory gives for water droplets at 550 nm, about 0.85 at 5 um rising to 0.87
/// at 15 um and beyond (Hansen and Travis 1974).
double dropletAsymmetry(double effectiveRadiusM);

}  // namespace cg::algo
