#pragma once
/// A velocity volume: an OpenVDB Vec3fGrid named "vel" (m/s) on a fog volume's transform, for
/// motion blur in a renderer that reads the VDB. Shared read-only between nodes; never kept
/// on disk (CloudVelocity makes it again from the particles in about the time a read takes).

#include <openvdb/openvdb.h>

#include "core/Data.h"

namespace cg {

class Registry;

class VelocityVolumeData final : public Data {
public:
    explicit VelocityVolumeData(openvdb::Vec3fGrid::ConstPtr grid);

    const openvdb::Vec3fGrid::ConstPtr grid;

    std::string typeName() const override { return "VelocityVolume"; }
    std::size_t byteSize() const override { return sizeof(*this) + grid->memUsage(); }
    bool serialize(ByteWriter&) const override { return false; }
};

void registerVelocityVolumeType(Registry& registry);

}  // namespace cg
