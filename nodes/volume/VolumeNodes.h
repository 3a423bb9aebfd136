#pragma once
/// Cloud particles to OpenVDB fog volumes, volume and point writers, and the VDB reader.

#include <cstdint>
#include <string>

namespace cg {

class Registry;
class ParamSet;

void registerVoxelizerNode(Registry& registry);       // Voxelizer
void registerWriteVdbNode(Registry& registry);        // WriteVDB
void registerReadVdbNode(Registry& registry);         // ReadVDB
void registerWritePointsNode(Registry& registry);     // WritePoints: VDB Points
void registerCombineVolumesNode(Registry& registry);  // CombineVolumes
void registerCloudVelocityNode(Registry& registry);   // CloudVelocity: vel for motion blur

/// ReadVDB's checks that need the grid's voxels (every value finite; a domain the Renderer
/// can hold, from where the voxels lie), which loading leaves to the cook (ReadVDB's, the
/// Renderer's): `validate` reads the voxels too, so that it refuses what `run` would. `params` are
/// a ReadVDB node's, `nodeLocation` its place ("g.json:/nodes/read"). Throws InputError at
/// the node's file parameter, in the words of the cook.
void checkReadVdbVoxels(const ParamSet& params, const std::string& nodeLocation,
                        std::uint64_t maxBytes);

}  // namespace cg
