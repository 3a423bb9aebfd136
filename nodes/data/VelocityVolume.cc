#include "nodes/data/VelocityVolume.h"

#include <stdexcept>

#include "core/Registry.h"

namespace cg {

VelocityVolumeData::VelocityVolumeData(openvdb::Vec3fGrid::ConstPtr grid_) : grid(std::move(grid_))
{
    if (!grid) throw std::invalid_argument("VelocityVolume: null grid");
}

void registerVelocityVolumeType(Registry& registry)
{
    openvdb::initialize();
    registry.addDataType({"VelocityVolume",
                          "an OpenVDB velocity grid (Vec3fGrid 'vel', m/s) on a fog volume's "
                          "transform, for motion blur",
                          [](ByteReader&) -> DataPtr {
                              throw std::invalid_argument(
                                  "VelocityVolume: never stored, so never read back");
                          }});
}

}  // namespace cg
