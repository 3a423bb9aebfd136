#pragma once
/// The recursive mapping of Sec. 5.2: source selection and on-demand cloud particles.

namespace cg {

class Registry;

void registerPrimitiveMapperNode(Registry& registry);      // PrimitiveMapper
void registerGenerateCloudNode(Registry& registry);        // GenerateCloud
void registerWriteCloudParticlesNode(Registry& registry);  // WriteCloudParticles
void registerPrimitiveSubsetNode(Registry& registry);      // PrimitiveSubset

}  // namespace cg
