#pragma once
/// Which tower a particle rose in, and where that tower's axis is, for the outflow that
/// spreads the top of a tower into an anvil (ours, the paper has no anvil).

#include <cstddef>
#include <cstdint>
#include <vector>

namespace cg::algo {

/// Towers are the connected groups (8 neighbours) of ground cells of `cellSize` metres that
/// hold at least one particle's start position (x0, y0): separate bubbles of the emission
/// map rise as separate towers. Ids 0, 1, ... in the order of the first particle of each.
/// The grid is coarsened when the start positions span more than 4 million cells.
std::vector<std::uint32_t> towerIds(const float* x0, const float* y0, std::size_t n,
                                    double cellSize);

/// Per particle, the axis of its tower now: the mean x, y of the tower's particles at or above
/// `bottom` (m), summed in particle order so the result does not depend on threads. Particles
/// of a tower with none there get their own position.
void towerAxes(const std::vector<std::uint32_t>& ids, const float* x, const float* y,
               const float* z, float bottom, std::vector<float>& axisX, std::vector<float>& axisY);

}  // namespace cg::algo
