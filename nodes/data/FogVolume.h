#pragma once
/// A fog volume: an OpenVDB FloatGrid of class fog volume named "density", finite values >= 0
/// (a fog density in [0, 1], or above 1 where the Voxelizer's water optics or a read VDB put them),
/// whose transform carries the voxel size in metres. Shared read-only between nodes.

#include <openvdb/openvdb.h>

#include "core/Data.h"

namespace cg {

class Registry;

class FogVolumeData final : public Data {
public:
    explicit FogVolumeData(openvdb::FloatGrid::ConstPtr grid);

    const openvdb::FloatGrid::ConstPtr grid;

    std::string typeName() const override { return "FogVolume"; }
    std::size_t byteSize() const override;
    /// In FogVolumeCodec's checked format (not OpenVDB's stream format, whose reader crashes
    /// on mutated bytes); false for a grid that format does not hold exactly.
    bool serialize(ByteWriter& out) const override;
};

/// Registers the type and initialises OpenVDB (idempotent).
void registerFogVolumeType(Registry& registry);

}  // namespace cg
