#pragma once
/// A 2D scalar map over the ground (x-y plane): nx * ny cells of cellSize metres, row-major
/// (index = iy * nx + ix). Cell (ix, iy) covers [ix, ix+1) * cellSize by [iy, iy+1) * cellSize,
/// so the map's corner is at the origin.

#include <cstdint>
#include <vector>

#include "core/Data.h"

namespace cg {

class Registry;

class Map2DData final : public Data {
public:
    Map2DData(int nx, int ny, double cellSize, std::vector<float> values);

    const int nx;
    const int ny;
    const double cellSize;  ///< metres
    const std::vector<float> values;

    float at(int ix, int iy) const { return values[static_cast<std::size_t>(iy) * nx + ix]; }
    /// The cell containing ground point (x, y), clamped to the map.
    std::int64_t cellAt(double x, double y) const;

    std::string typeName() const override { return "Map2D"; }
    std::size_t byteSize() const override { return sizeof(*this) + values.size() * sizeof(float); }
    bool serialize(ByteWriter& out) const override;
};

/// Throws std::runtime_error ("Map2D: ...") unless the size is sane, matches the values, the
/// cell size is finite and positive and every value lies in [0, 1] (the mapper's fNoise).
/// Values from outside the engine (the disk cache, Python) pass it before they are used.
void checkMap2D(std::uint64_t nx, std::uint64_t ny, double cell, const std::vector<float>& values);

void registerMap2DType(Registry& registry);

}  // namespace cg
