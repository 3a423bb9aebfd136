#pragma once
/// Hero clouds (ours): thermals placed where a shot's layout wants a cloud, whatever the
/// density map says there. Each is a disk on the ground, a centre (x, y), a radius and a
/// start time: its cells take density 1 within half the radius, falling smoothly
/// (smoothstep) to 0 at the radius, wherever that is above the map's own value, and the
/// vapour they emit waits at its start until the start time. No engine includes.

#include <cstdint>
#include <vector>

namespace cg::algo {

struct HeroCloud {
    double x = 0.0, y = 0.0;  ///< centre on the ground, m
    double radius = 500.0;    ///< m
    double start = 0.0;       ///< s after the simulation's first frame
};

/// Numbers a hero takes in a flat list: x, y, radius, start.
inline constexpr std::size_t kNumbersPerHeroCloud = 4;

/// The heroes of a flat list [x, y, radius, start, ...]. Throws std::invalid_argument naming
/// the hero for a list whose length is not a multiple of 4, a radius not > 0, a start < 0 or
/// a value that is not finite.
std::vector<HeroCloud> heroCloudsFromList(const std::vector<double>& numbers);

/// A hero's density at distance r from its centre.
double heroDensity(double r, double radius);

/// Raises `values` (an nx x ny map of cells of `cell` metres, row-major) to the heroes'
/// densities at the cell centres where those are higher, and returns for each cell the hero
/// that raised it (the first of the highest), or -1.
std::vector<std::int32_t> stampHeroClouds(int nx, int ny, double cell, std::vector<float>& values,
                                          const std::vector<HeroCloud>& heroes);

}  // namespace cg::algo
