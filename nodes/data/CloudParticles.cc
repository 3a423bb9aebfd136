#include "nodes/data/CloudParticles.h"

#include <stdexcept>

#include "core/Registry.h"

namespace cg {

CloudParticlesData::CloudParticlesData(std::vector<float> positions_, std::vector<std::uint8_t> levels_,
                                       std::vector<std::uint32_t> sources_)
    : positions(std::move(positions_)), levels(std::move(levels_)), sources(std::move(sources_))
{
    if (positions.size() != 3 * levels.size() || sources.size() != levels.size())
        throw std::invalid_argument("CloudParticles: arrays differ in length");
}

std::size_t CloudParticlesData::byteSize() const
{
    return sizeof(*this) + positions.size() * sizeof(float) + levels.size() + sources.size() * 4;
}

bool CloudParticlesData::serialize(ByteWriter& out) const
{
    out.podVector(positions);
    out.podVector(levels);
    out.podVector(sources);
    return true;
}

void registerCloudParticlesType(Registry& registry)
{
    registry.addDataType({"CloudParticles", "cloud particles of one frame: position, level, source id",
                          [](ByteReader& in) -> DataPtr {
                              auto positions = in.podVector<float>();
                              auto levels = in.podVector<std::uint8_t>();
                              auto sources = in.podVector<std::uint32_t>();
                              return std::make_shared<CloudParticlesData>(
                                  std::move(positions), std::move(levels), std::move(sources));
                          }});
}

}  // namespace cg
