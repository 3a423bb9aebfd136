#pragma once
/// Volume rendering of fog volumes, image writers, and a synthetic test cloud.

namespace cg {

class Registry;

void registerRendererNode(Registry& registry);          // Renderer
void registerWriteImageNode(Registry& registry);        // WriteImage
void registerWriteCameraNode(Registry& registry);       // WriteCamera
void registerWriteShotNode(Registry& registry);         // WriteShot: the shot as JSON
void registerSyntheticCumulusNode(Registry& registry);  // SyntheticCumulus

}  // namespace cg
