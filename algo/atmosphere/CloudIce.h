#pragma once
/// Glaciation: the condensate of a deep cloud's cold upper part freezes, and ice scatters
/// light differently from droplets (ours: the paper's clouds have no phase; cloud physics
/// gives it).
///
/// Freezing: pure droplets stay liquid well below 0 C. Ice nuclei start freezing some of them
/// near -10 C and every droplet freezes homogeneously by -38 C (Pruppacher and Klett 1997,
/// ch. 7; Rosenfeld and Woodley 2000 measured liquid water in vigorous Texas updrafts down to
/// -37.5 C). Between the two the ice share of the condensate rises linearly with cooling (a
/// choice of ours; weather models use similar ramps, e.g. the ECMWF IFS's quadratic one from
/// 0 to -23 C).
///
/// Fallout: ice crystals grow at the droplets' expense and aggregate into snow that falls out
/// of the updraft; the anvil keeps a small share of the frozen condensate. Anvils measured by
/// aircraft hold about 0.01-1 g/m^3 of ice, a tenth of a gram near the storm (Garrett et al.
/// 2005; Stith et al. 2014): `retention` is that share (ours).
///
/// Optics: crystals are much larger than droplets (effective radius 20-60 um in anvils) and
/// less dense, so in geometric optics sigma = 3 IWC / (2 rho_ice r_eff) (Foot 1988; Fu 1996
/// in the large-crystal limit): a tenth of a gram of anvil ice per m^3 has a mean free path of
/// a few hundred metres where the same water as droplets has one of a few tens, and the ice
/// sheet is translucent at its edges.

namespace cg::algo {

inline constexpr double kIceDensity = 917.0;  ///< rho_ice, kg/m^3

/// How a cloud's condensate turns to ice.
struct Glaciation {
    double startC = -10.0;           ///< first ice, C
    double endC = -38.0;             ///< all ice, C (below startC)
    double retention = 0.05;         ///< share of the frozen condensate kept as cloud ice
    double effectiveRadius = 30e-6;  ///< ice crystals' r_eff, m
};

/// Throws std::invalid_argument unless endC < startC, retention in (0, 1] and the radius in
/// (0, 1 mm].
void checkGlaciation(const Glaciation& g);

/// The share of the condensate that is ice at temperature tC: 0 at and above startC, 1 at
/// and below endC, linear between.
double iceFraction(double tC, const Glaciation& g);

/// sigma in 1/m of IWC g/m^3 of crystals of effective radius rEff metres.
double extinctionFromIce(double iwcGramsPerM3, double rEff);

}  // namespace cg::algo
