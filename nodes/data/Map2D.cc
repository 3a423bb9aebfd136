#include "nodes/data/Map2D.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/Registry.h"

namespace cg {

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
    registry.addDataType({"Map2D", "a 2D scalar map over the ground, nx x ny cells",
                          [](ByteReader& in) -> DataPtr {
                              const auto nx = in.u64();
                              const auto ny = in.u64();
                              const double cell = in.f64();
                              auto values = in.podVector<float>();
                              if (nx > (1u << 30) || ny > (1u << 30))
                                  throw std::runtime_error("Map2D: absurd size");
                              return std::make_shared<Map2DData>(static_cast<int>(nx),
                                                                 static_cast<int>(ny), cell,
                                                                 std::move(values));
                          }});
}

}  // namespace cg
