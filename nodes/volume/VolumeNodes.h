#pragma once
/// Cloud particles to OpenVDB fog volumes, and volume and point writers.

namespace cg {

class Registry;

void registerVoxelizerNode(Registry& registry);    // Voxelizer
void registerWriteVdbNode(Registry& registry);     // WriteVDB
void registerWritePointsNode(Registry& registry);  // WritePoints: VDB Points
void registerCombineVolumesNode(Registry& registry);  // CombineVolumes

}  // namespace cg
