#pragma once
/// The physical half of the hybrid method (Sec. 4): the particle-based fluid simulation that
/// makes the 3D cloud primitive set, and loading a stored one.

namespace cg {

class Registry;

void registerPrimitiveSimNode(Registry& registry);     // PrimitiveSim
void registerPrimitiveLoadNode(Registry& registry);    // PrimitiveLoad
void registerWritePrimitiveNodes(Registry& registry);  // WritePrimitive, WritePrimitivePly
void registerPrimitiveFrameNode(Registry& registry);   // PrimitiveFrame

}  // namespace cg
