#pragma once
/// Cloud particles to OpenVDB fog volumes, volume and point writers, and the VDB reader.

namespace cg {

class Registry;

void registerVoxelizerNode(Registry& registry);    // Voxelizer
void registerWriteVdbNode(Registry& registry);     // WriteVDB
void registerReadVdbNode(Registry& registry);      // ReadVDB
void registerWritePointsNode(Registry& registry);  // WritePoints: VDB Points
void registerCombineVolumesNode(Registry& registry);  // CombineVolumes

}  // namespace cg
