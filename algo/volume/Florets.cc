#include "algo/volume/Florets.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "algo/CounterRandom.h"

namespace cg::algo {

namespace {

/// Root cells per root radius (ours): a root every r^3 keeps the lumps touching when the
/// roots of overlapping copies, each kept in its own territory, fall at random.
constexpr double kRootCell = 1.0;
/// A child's centre lies this share of its parent's radius from the parent's centre.
constexpr double kChildOffset = 0.75;
/// Children point no further down than this vertical component (sin 60 degrees).
constexpr double kLowestChildZ = -0.866;

double uniform(std::uint64_t bits, int field)
{
    return static_cast<double>((bits >> (21 * field)) & 0x1fffff) * 0x1.0p-21;
}

struct Walk {
    const double* x;
    const FloretSettings& s;
    double prune;
    double enough;
    double best = -1e30;

    void visit(const double c[3], double r, std::uint64_t id, int level)
    {
        const double d = std::sqrt((x[0] - c[0]) * (x[0] - c[0]) + (x[1] - c[1]) * (x[1] - c[1]) +
                                   (x[2] - c[2]) * (x[2] - c[2]));
        best = std::max(best, r - d);
        // Descendants lie within kFloretReach r of the centre: none can beat the best so
        // far, or matter to the caller, when that bound does not.
        if (level + 1 >= s.levels || kFloretReach * r - d <= std::max(prune, best) ||
            best >= enough)
            return;
        for (int i = 0; i < s.children; ++i) {
            const std::uint64_t child = mix64(id ^ static_cast<std::uint64_t>(i + 1));
            // A direction uniform on the sphere: z uniform, azimuth uniform.
            const double z = 2.0 * uniform(child, 0) - 1.0;
            if (z < kLowestChildZ) continue;
            const double azimuth = 2.0 * M_PI * uniform(child, 1);
            const double ring = std::sqrt(std::max(0.0, 1.0 - z * z));
            const double offset = kChildOffset * r;
            const double cc[3] = {c[0] + offset * ring * std::cos(azimuth),
                                  c[1] + offset * ring * std::sin(azimuth), c[2] + offset * z};
            visit(cc, 0.5 * r, child, level + 1);
        }
    }
};

}  // namespace

void checkFloretSettings(const FloretSettings& s)
{
    if (!(s.radius > 0.0) || !std::isfinite(s.radius))
        throw std::invalid_argument("florets: radius must be > 0 metres");
    if (s.levels < 1 || s.levels > 6)
        throw std::invalid_argument("florets: levels must lie in 1..6");
    if (s.children < 1 || s.children > 16)
        throw std::invalid_argument("florets: children must lie in 1..16");
}

void gatherGeneration(const double lo[3], const double hi[3], const FloretSettings& s,
                      int generation, const RootTest& acceptRoot, std::vector<FloretRoot>& roots)
{
    const double radius = std::ldexp(s.radius, -generation);
    const double cell = kRootCell * radius, reach = kFloretReach * radius;
    const std::uint64_t seed = counterBits(s.seed, 0xf10e7, static_cast<std::uint64_t>(generation));
    std::int64_t first[3], last[3];
    for (int a = 0; a < 3; ++a) {
        first[a] = static_cast<std::int64_t>(std::floor((lo[a] - reach) / cell));
        last[a] = static_cast<std::int64_t>(std::floor((hi[a] + reach) / cell));
    }
    for (std::int64_t cx = first[0]; cx <= last[0]; ++cx)
        for (std::int64_t cy = first[1]; cy <= last[1]; ++cy)
            for (std::int64_t cz = first[2]; cz <= last[2]; ++cz) {
                const std::uint64_t id = mix64(mix64(mix64(seed ^ static_cast<std::uint64_t>(cx)) ^
                                                     static_cast<std::uint64_t>(cy)) ^
                                               static_cast<std::uint64_t>(cz));
                FloretRoot root{{(static_cast<double>(cx) + uniform(id, 0)) * cell,
                                 (static_cast<double>(cy) + uniform(id, 1)) * cell,
                                 (static_cast<double>(cz) + uniform(id, 2)) * cell},
                                radius,
                                id,
                                generation};
                // Only roots whose lumps can reach the box.
                double gap2 = 0.0;
                for (int a = 0; a < 3; ++a) {
                    const double gap =
                        std::max({lo[a] - root.centre[a], root.centre[a] - hi[a], 0.0});
                    gap2 += gap * gap;
                }
                if (gap2 <= reach * reach && acceptRoot(root.centre, radius)) roots.push_back(root);
            }
}

std::vector<FloretRoot> gatherRoots(const double lo[3], const double hi[3], const FloretSettings& s,
                                    const RootTest& acceptRoot)
{
    std::vector<FloretRoot> roots;
    for (int generation = 0; generation < s.levels; ++generation)
        gatherGeneration(lo, hi, s, generation, acceptRoot, roots);
    return roots;
}

double floretDepth(const double x[3], const FloretSettings& s, const std::vector<FloretRoot>& roots,
                   double prune, double enough)
{
    Walk walk{x, s, prune, enough};
    for (const FloretRoot& root : roots) {
        walk.visit(root.centre, root.radius, root.id, root.generation);
        if (walk.best >= enough) break;
    }
    return walk.best;
}

}  // namespace cg::algo
