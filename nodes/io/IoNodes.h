#pragma once
/// Writers of maps and particles.

namespace cg {

class Registry;

void registerWriteMapNode(Registry& registry);        // WriteMap: PFM + 16-bit PNG preview
void registerWriteParticlesNode(Registry& registry);  // WriteParticles: binary PLY

}  // namespace cg
