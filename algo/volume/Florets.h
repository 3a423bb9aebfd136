#pragma once
/// Cauliflower florets: round lumps on round lumps, the relief of a cumulus turret.
///
/// A forest of sphere trees. The roots are one feature point per cubic cell of edge r
/// (counter-hashed, so the same on every machine and thread), kept where the caller says
/// the point lies within a layer under the cloud's surface; each has radius r. Every
/// sphere of radius r carries `children` spheres of radius r / 2 centred 0.75 r from its
/// centre in random directions that do not point down more than 60 degrees, so each child
/// stands a quarter of its parent's radius out of it, down `levels` generations. The union of
/// the spheres is convex lumps with creases between them and smaller lumps on every lump, the
/// look of a cauliflower and of a sunlit cumulus (Ludlam and Scorer 1953 describe the
/// turrets; the construction and its numbers are ours). A point's value is how far inside
/// the union it lies: max over spheres of (radius - distance to the centre). No engine
/// includes.

#include <cstdint>
#include <functional>
#include <vector>

namespace cg::algo {

struct FloretSettings {
    /// Radius r0 of the largest lumps, metres (> 0).
    double radius = 200.0;
    /// Generations of lumps, each half the radius of the one before (1..6).
    int levels = 4;
    /// Children per lump (1..16).
    int children = 8;
    std::uint64_t seed = 0;
};

/// Throws std::invalid_argument naming the bad setting.
void checkFloretSettings(const FloretSettings& s);

/// How far (metres) the children of a lump of radius r can reach past its centre beyond r:
/// the union of a root and its descendants lies within 1.5 r of the root's centre.
inline constexpr double kFloretReach = 1.5;

/// Whether a root of the given radius at p (the coordinates of x) is part of the cloud.
using RootTest = std::function<bool(const double p[3], double radius)>;

/// A root the caller kept: its centre, radius, hash and generation.
struct FloretRoot {
    double centre[3];
    double radius;
    std::uint64_t id;
    int generation;
};

/// The roots of every generation whose lumps can reach the box [lo, hi] and that
/// `acceptRoot` keeps: generation g's are one a cell of edge r0 / 2^g, radius r0 / 2^g,
/// with `levels - g` generations on them, so a thin part of the cloud that holds no root of
/// the largest size holds smaller ones. Gathered once for a block of points.
std::vector<FloretRoot> gatherRoots(const double lo[3], const double hi[3], const FloretSettings& s,
                                    const RootTest& acceptRoot);

/// gatherRoots' roots of one generation, appended to `roots`.
void gatherGeneration(const double lo[3], const double hi[3], const FloretSettings& s,
                      int generation, const RootTest& acceptRoot, std::vector<FloretRoot>& roots);

/// How far inside the union of the roots' florets x lies (metres; negative outside; -1e30
/// without roots). `prune` (metres) is the least value the caller cares about: lumps whose
/// every descendant lies farther out are skipped; once the value reaches `enough` the walk
/// stops and returns it (a value >= enough, not the maximum).
double floretDepth(const double x[3], const FloretSettings& s, const std::vector<FloretRoot>& roots,
                   double prune, double enough = 1e30);

}  // namespace cg::algo
