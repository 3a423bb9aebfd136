#include "nodes/data/Map2D.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/Registry.h"
#include "nodes/data/ValueChecks.h"

namespace cg {

namespace {

constexpr const char* kType = "Map2D";
constexpr std::uint64_t kMaxSide = std::uint64_t{1} << 30;

}  // namespace

void checkMap2D(std::uint64_t nx, std::uint64_t ny, double cell, const std::vector<float>& values)
{
    if (nx == 0 || ny == 0 || nx > kMaxSide || ny > kMaxSide)
        checks::refuse(kType,
                       "size " + std::to_string(nx) + " x " + std::to_string(ny) + " is absurd");
    if (values.size() != nx * ny)
        checks::refuse(kType, std::to_string(values.size()) + " values for " + std::to_string(nx) +
                                  " x " + std::to_string(ny) + " cells");
    // Ground positions are divided by the cell size to find a cell.
    if (!(cell > 0.0) || !std::isfinite(cell))
        checks::refuse(kType, "cell size " + std::to_string(cell) + " is not finite and positive");
    // fNoise is a density in [0, 1] (NoiseMap normalises to it); the mapper's speeds
    // A = 1 + A0 fNoise and scales R = R0 fNoise assume it, and NaN would pick no cell.
    for (std::size_t i = 0; i < values.size(); ++i)
        if (!(values[i] >= 0.0f && values[i] <= 1.0f))
            checks::refuse(kType, "value " + std::to_string(values[i]) + " of cell " +
                                      std::to_string(i) + " is outside [0, 1]");
}

namespace {

DataPtr readMap2D(ByteReader& in)
{
    const std::uint64_t nx = in.u64();
    const std::uint64_t ny = in.u64();
    const double cell = in.f64();
    auto values = in.podVector<float>();
    checkMap2D(nx, ny, cell, values);
    return std::make_shared<Map2DData>(static_cast<int>(nx), static_cast<int>(ny), cell,
                                       std::move(values));
}

}  // namespace

Map2DData::Map2DData(int nx_, int ny_, double cellSize_, std::vector<float> values_)
    : nx(nx_), ny(ny_), cellSize(cellSize_), values(std::move(values_))
{
    if (nx <= 0 || ny <= 0 || !(cellSize > 0.0) ||
        values.size() != static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny))
        throw std::invalid_argument("Map2D: size does not match its values");
}

std::int64_t Map2DData::cellAt(double x, double y) const
{
    const auto ix = static_cast<std::int64_t>(std::clamp(std::floor(x / cellSize), 0.0, nx - 1.0));
    const auto iy = static_cast<std::int64_t>(std::clamp(std::floor(y / cellSize), 0.0, ny - 1.0));
    return iy * nx + ix;
}

bool Map2DData::serialize(ByteWriter& out) const
{
    out.u64(static_cast<std::uint64_t>(nx));
    out.u64(static_cast<std::uint64_t>(ny));
    out.f64(cellSize);
    out.podVector(values);
    return true;
}

void registerMap2DType(Registry& registry)
{
    registry.addDataType({"Map2D", "a 2D scalar map over the ground, nx x ny cells", readMap2D});
}

}  // namespace cg
