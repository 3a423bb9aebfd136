#pragma once
/// Volume rendering of fog volumes, and image writers.

namespace cg {

class Registry;

void registerRendererNode(Registry& registry);     // Renderer
void registerWriteImageNode(Registry& registry);   // WriteImage

}  // namespace cg
