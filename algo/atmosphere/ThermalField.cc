#include "algo/atmosphere/ThermalField.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "algo/CounterRandom.h"
#include "algo/atmosphere/HeroClouds.h"

namespace cg::algo {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr std::uint64_t kSizeStream = 0x5468657253697a65ull;   // "TherSize"
constexpr std::uint64_t kPlaceStream = 0x546865725768657eull;  // "TherWhe~"
constexpr std::uint64_t kStartStream = 0x5468657253746172ull;  // "TherStar"

/// A thermal's disk radius from its diameter (the density >= 0.5 region is 3/4 of the disk).
double radiusOf(double diameter) { return diameter / 1.5; }

/// The thermals' diameters, drawn until their density >= 0.5 areas add up to the cover's
/// share of the ground, largest first.
std::vector<double> drawDiameters(const ThermalFieldSettings& s)
{
    const double ground = s.nx * s.cellSize * s.ny * s.cellSize;
    std::vector<double> d;
    double area = 0.0;
    for (std::uint64_t i = 0; area < s.cover * ground; ++i) {
        if (i >= kMaxThermals)
            throw std::invalid_argument("the field needs more than " +
                                        std::to_string(kMaxThermals) + " thermals");
        d.push_back(powerLawDiameter(counterUniform(s.seed, kSizeStream, i), s.smallest, s.largest,
                                     s.exponent));
        area += 0.25 * kPi * d.back() * d.back();
    }
    std::sort(d.begin(), d.end(), [](double a, double b) { return a > b; });
    return d;
}

/// Placed disks in buckets of a square lattice as wide as the largest disk's reach, so an
/// overlap test looks at 3 x 3 buckets.
class DiskGrid {
public:
    DiskGrid(double width, double height, double reach)
        : mCell(reach),
          mNx(std::max(1, static_cast<int>(std::ceil(width / reach)))),
          mNy(std::max(1, static_cast<int>(std::ceil(height / reach)))),
          mBuckets(static_cast<std::size_t>(mNx) * static_cast<std::size_t>(mNy))
    {
    }

    /// Whether a disk of radius r at (x, y) keeps `gap` times the larger radius from every
    /// placed disk.
    bool free(double x, double y, double r, double gap) const
    {
        const int bx = bucket(x, mNx), by = bucket(y, mNy);
        for (int j = std::max(0, by - 1); j <= std::min(mNy - 1, by + 1); ++j)
            for (int i = std::max(0, bx - 1); i <= std::min(mNx - 1, bx + 1); ++i)
                for (const Disk& d : mBuckets[index(i, j)]) {
                    const double apart = r + d.r + gap * std::max(r, d.r);
                    if (std::hypot(x - d.x, y - d.y) < apart) return false;
                }
        return true;
    }

    void add(double x, double y, double r)
    {
        mBuckets[index(bucket(x, mNx), bucket(y, mNy))].push_back({x, y, r});
    }

private:
    struct Disk {
        double x, y, r;
    };
    int bucket(double v, int n) const
    {
        return std::clamp(static_cast<int>(std::floor(v / mCell)), 0, n - 1);
    }
    std::size_t index(int i, int j) const
    {
        return static_cast<std::size_t>(j) * static_cast<std::size_t>(mNx) +
               static_cast<std::size_t>(i);
    }
    double mCell;
    int mNx, mNy;
    std::vector<std::vector<Disk>> mBuckets;
};

}  // namespace

double powerLawDiameter(double u, double smallest, double largest, double exponent)
{
    // n(l) ~ l^b on [a, c]: F(l) = (l^(b+1) - a^(b+1)) / (c^(b+1) - a^(b+1)).
    const double k = exponent + 1.0;
    const double a = std::pow(smallest, k), c = std::pow(largest, k);
    return std::pow(a + u * (c - a), 1.0 / k);
}

void checkThermalField(const ThermalFieldSettings& s)
{
    using Setting = ThermalFieldError::Setting;
    const auto fail = [](Setting setting, const std::string& what) {
        throw ThermalFieldError(setting, what);
    };
    if (s.nx < 1 || s.ny < 1 || !(s.cellSize > 0.0) || !std::isfinite(s.cellSize))
        fail(Setting::Map, "the map needs at least one cell of positive size");
    if (!(s.smallest > 0.0) || !(s.largest >= s.smallest) || !std::isfinite(s.largest))
        fail(Setting::Sizes, "smallest must be > 0 and largest >= smallest");
    if (!(s.exponent >= -4.0 && s.exponent <= 0.0) || std::abs(s.exponent + 1.0) < 1e-9)
        fail(Setting::Exponent, "the exponent must be in [-4, 0] and not -1");
    if (!(s.cover > 0.0 && s.cover <= 0.6)) fail(Setting::Cover, "the cover must be in (0, 0.6]");
    if (!(s.gap >= 0.0 && s.gap <= 4.0)) fail(Setting::Gap, "the gap must be in [0, 4]");
    if (!(s.fullScaleCloud > 0.0 && std::isfinite(s.fullScaleCloud)))
        fail(Setting::FullScale, "the full-scale cloud diameter must be > 0");
    // The expected count from the mean area of the law, before drawing any.
    const double k2 = s.exponent + 3.0, k1 = s.exponent + 1.0;
    const double norm = (std::pow(s.largest, k1) - std::pow(s.smallest, k1)) / k1;
    const double meanSquare =
        s.largest == s.smallest
            ? s.smallest * s.smallest
            : (std::abs(k2) < 1e-12 ? std::log(s.largest / s.smallest)
                                    : (std::pow(s.largest, k2) - std::pow(s.smallest, k2)) / k2) /
                  norm;
    const double ground = s.nx * s.cellSize * s.ny * s.cellSize;
    const double expected = s.cover * ground / (0.25 * kPi * meanSquare);
    if (!(expected < 0.5 * static_cast<double>(kMaxThermals)))
        fail(Setting::Cover, "the field would need about " +
                                 std::to_string(static_cast<long long>(expected)) +
                                 " thermals, more than " + std::to_string(kMaxThermals / 2) +
                                 ": raise smallest or lower the cover");
}

ThermalField placeThermals(const ThermalFieldSettings& s)
{
    checkThermalField(s);
    const std::vector<double> diameters = drawDiameters(s);
    const double width = s.nx * s.cellSize, height = s.ny * s.cellSize;
    const double reach = radiusOf(diameters.front()) * (2.0 + s.gap);
    DiskGrid grid(width, height, reach);
    ThermalField field;
    for (std::size_t i = 0; i < diameters.size(); ++i) {
        const double r = radiusOf(diameters[i]);
        bool placed = false;
        for (int t = 0; t < kPlacementTries && !placed; ++t) {
            const std::uint64_t draw = 2 * (i * kPlacementTries + static_cast<std::uint64_t>(t));
            const double x = counterUniform(s.seed, kPlaceStream, draw) * width;
            const double y = counterUniform(s.seed, kPlaceStream, draw + 1) * height;
            if (!grid.free(x, y, r, s.gap)) continue;
            grid.add(x, y, r);
            field.thermals.push_back({x, y, diameters[i]});
            placed = true;
        }
        if (!placed) ++field.leftOut;
    }
    return field;
}

namespace {

/// The thermals as disks stamped on the map: each cell's density and the thermal it has it
/// from (-1: none).
std::vector<std::int32_t> stampThermals(const ThermalFieldSettings& s, const ThermalField& field,
                                        std::vector<float>& values)
{
    std::vector<HeroCloud> disks;
    for (const Thermal& t : field.thermals) disks.push_back({t.x, t.y, radiusOf(t.diameter), 0.0});
    values.assign(static_cast<std::size_t>(s.nx) * static_cast<std::size_t>(s.ny), 0.0f);
    return stampHeroClouds(s.nx, s.ny, s.cellSize, values, disks);
}

}  // namespace

std::vector<float> thermalMap(const ThermalFieldSettings& s, const ThermalField& field)
{
    std::vector<float> values;
    stampThermals(s, field, values);
    return values;
}

std::vector<float> thermalStartMap(const ThermalFieldSettings& s, const ThermalField& field)
{
    std::vector<float> values;
    const std::vector<std::int32_t> owner = stampThermals(s, field, values);
    for (std::size_t i = 0; i < values.size(); ++i)
        values[i] = owner[i] < 0 ? 0.0f
                                 : static_cast<float>(counterUniform(
                                       s.seed, kStartStream, static_cast<std::uint64_t>(owner[i])));
    return values;
}

std::vector<float> thermalScaleMap(const ThermalFieldSettings& s, const ThermalField& field)
{
    std::vector<float> values;
    std::vector<std::int32_t> owner = stampThermals(s, field, values);
    // Breadth-first from every stamped cell in row order: each other cell takes the owner
    // that reaches it in the fewest steps (the first in that order on a tie).
    std::vector<std::size_t> queue;
    for (std::size_t i = 0; i < owner.size(); ++i)
        if (owner[i] >= 0) queue.push_back(i);
    const auto nx = static_cast<std::size_t>(s.nx), ny = static_cast<std::size_t>(s.ny);
    for (std::size_t head = 0; head < queue.size(); ++head) {
        const std::size_t i = queue[head], x = i % nx, y = i / nx;
        const std::size_t next[4] = {x + 1 < nx ? i + 1 : i, x > 0 ? i - 1 : i,
                                     y + 1 < ny ? i + nx : i, y > 0 ? i - nx : i};
        for (const std::size_t j : next)
            if (owner[j] < 0) {
                owner[j] = owner[i];
                queue.push_back(j);
            }
    }
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (owner[i] < 0) {
            values[i] = 1.0f;
            continue;
        }
        const double l = field.thermals[static_cast<std::size_t>(owner[i])].diameter;
        values[i] = static_cast<float>(std::min(1.0, l / s.fullScaleCloud));
    }
    return values;
}

}  // namespace cg::algo
