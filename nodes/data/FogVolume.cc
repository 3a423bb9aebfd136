#include "nodes/data/FogVolume.h"

#include <stdexcept>

#include "core/Registry.h"
#include "nodes/data/FogVolumeCodec.h"

namespace cg {

FogVolumeData::FogVolumeData(openvdb::FloatGrid::ConstPtr grid_) : grid(std::move(grid_))
{
    if (!grid) throw std::invalid_argument("FogVolume: null grid");
}

std::size_t FogVolumeData::byteSize() const { return sizeof(*this) + grid->memUsage(); }

bool FogVolumeData::serialize(ByteWriter& out) const { return encodeFogVolume(*grid, out); }

void registerFogVolumeType(Registry& registry)
{
    openvdb::initialize();
    registry.addDataType({"FogVolume",
                          "an OpenVDB fog volume (FloatGrid 'density', values >= 0: fog density in "
                          "[0, 1], above 1 with water optics)",
                          [](ByteReader& in) -> DataPtr {
                              return std::make_shared<FogVolumeData>(decodeFogVolume(in));
                          }});
}

}  // namespace cg
