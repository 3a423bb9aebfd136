#pragma once
/// A cumulus field's thermals with the size statistics of real fields (ours): cloud
/// diameters l drawn from a power-law number density n(l) ~ l^b between a smallest and a
/// largest cloud, placed at random on the ground without overlapping until they cover a
/// chosen fraction of it, and stamped as a density map for the VapourEmitter and mapper.
///
/// The physics it rests on: the number density of shallow-cumulus sizes falls as a power law
/// with b about -1.7 in large-eddy simulations (Neggers, Jonker and Siebesma 2003) and -1.7
/// to -2.5 in satellite studies, up to a scale break near the boundary layer's depth (1-2
/// km); fair-weather cover is 10-40%. Values and method are ours, not the paper's (the paper
/// draws one 1/f^beta map whose smoothness sets one size).
///
/// Each thermal is a disk whose density is 1 out to half its radius, falling smoothly to 0 at
/// its radius (heroDensity); its diameter l is that of its density >= 0.5 region, 1.5 times
/// its radius. Disks keep `gap` times the larger radius apart, so neighbours do not merge into
/// one cloud. Placement is random sequential adsorption, largest first: a thermal that finds
/// no free spot in kPlacementTries draws is left out (the result says how many; above about
/// 30% cover with the default gap the ground fills up). Every draw is
/// counter-based on (seed, thermal, try): the same settings give the same field.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace cg::algo {

struct ThermalFieldSettings {
    int nx = 400, ny = 400;   ///< map cells
    double cellSize = 50.0;   ///< m
    double cover = 0.25;      ///< fraction of the ground within l/2 of a thermal, (0, 0.6]
    double smallest = 200.0;  ///< smallest cloud diameter l, m
    double largest = 2000.0;  ///< largest cloud diameter l (the scale break), m
    double exponent = -1.7;   ///< b of n(l) ~ l^b, in [-4, -1) or (-1, 0]
    double gap = 0.25;        ///< disks keep this times the larger radius apart
    /// Diameter from which a thermal's copies take the mapper's full scale (thermalScaleMap).
    double fullScaleCloud = 300.0;
    std::uint64_t seed = 0;
};

struct Thermal {
    double x = 0.0, y = 0.0;  ///< centre, m
    double diameter = 0.0;    ///< l, m
};

struct ThermalField {
    std::vector<Thermal> thermals;  ///< placed, largest first
    std::uint64_t leftOut = 0;      ///< drawn but found no free spot
};

/// Draws that may fail before a thermal is left out.
inline constexpr int kPlacementTries = 256;

/// The most thermals a field may draw (a memory and time guard).
inline constexpr std::uint64_t kMaxThermals = 1u << 20;

/// Diameter number u in [0, 1) of the truncated power law: the inverse of its distribution.
double powerLawDiameter(double u, double smallest, double largest, double exponent);

/// An unusable setting, and which: the map's size, the cloud sizes, the exponent, the cover
/// (also a field that would need more than kMaxThermals thermals), the gap or the full-scale
/// diameter.
class ThermalFieldError : public std::invalid_argument {
public:
    enum class Setting { Map, Sizes, Exponent, Cover, Gap, FullScale };
    ThermalFieldError(Setting setting, const std::string& what)
        : std::invalid_argument(what), mSetting(setting)
    {
    }
    Setting setting() const { return mSetting; }

private:
    Setting mSetting;
};

/// Throws ThermalFieldError for an unusable setting.
void checkThermalField(const ThermalFieldSettings& s);

/// The field's thermals.
ThermalField placeThermals(const ThermalFieldSettings& s);

/// The density map (nx x ny, row-major, iy = 0 the y = 0 edge) of the thermals: each cell the
/// highest of their densities at its centre.
std::vector<float> thermalMap(const ThermalFieldSettings& s, const ThermalField& field);

/// Each thermal's start (ours): a map of the same cells holding, over each thermal's disk, a
/// value drawn uniformly in [0, 1) for that thermal (counter-based on the seed and its
/// index), 0 elsewhere. As the VapourEmitter's startDelay, thermals start one by one over
/// startDelayMax, each all at once, so a field keeps forming new clouds.
std::vector<float> thermalStartMap(const ThermalFieldSettings& s, const ThermalField& field);

/// The copies' scale over each thermal (ours): min(1, l / fullScaleCloud) for a thermal of
/// diameter l, over its disk and over every cell nearer to it than to any other disk (by
/// 4-connected steps), so a condensation particle the wind has carried off its disk still
/// reads its own thermal's scale. As the PrimitiveMapper's map (Eq. 16, R = R0 fNoise) a
/// thermal smaller than one copy's footprint makes one smaller copy, not one copy of the
/// same size: the clouds keep the thermals' size law below that footprint. A field without
/// thermals is all 1.
std::vector<float> thermalScaleMap(const ThermalFieldSettings& s, const ThermalField& field);

}  // namespace cg::algo
