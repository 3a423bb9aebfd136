#include "support/GridChecksum.h"

#include <cstring>

namespace cg::test {

std::uint64_t gridChecksum(const openvdb::FloatGrid& grid)
{
    std::uint64_t h = 14695981039346656037ull;
    const auto mix = [&h](std::uint32_t word) {
        for (int b = 0; b < 4; ++b) h = (h ^ ((word >> (8 * b)) & 0xffu)) * 1099511628211ull;
    };
    for (auto it = grid.tree().cbeginValueOn(); it; ++it) {
        const openvdb::Coord c = it.getCoord();
        for (int a = 0; a < 3; ++a) mix(static_cast<std::uint32_t>(c[a]));
        std::uint32_t bits;
        std::memcpy(&bits, &*it, sizeof(bits));
        mix(bits);
    }
    return h;
}

}  // namespace cg::test
