#pragma once
/// Cloud particles to OpenVDB fog volumes, and volume writers.

namespace cg {

class Registry;

void registerVoxelizerNode(Registry& registry);    // Voxelizer
void registerWriteVdbNode(Registry& registry);     // WriteVDB

}  // namespace cg
